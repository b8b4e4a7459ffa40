package io.robomw.agents.messaging.robot;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.Robot;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.Serializable;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;

/**
 * Serves a local {@link Robot} to remote callers ({@link RemoteRobot},
 * {@code Robots.remote("tcp://host:port/name")}): answers each {@link RobotCall} on the robot's
 * topic with a {@link RobotReply} once the robot has done it. Motions run asynchronously, so the
 * messaging thread is never held while a robot moves; concurrent callers follow the robot's own
 * rules (most recent motion wins). A caller whose wait ends early cancels its call
 * ({@link RobotCall.Cancel}): the robot's future is cancelled, which ends its command. A
 * {@code stop()} is answered once the robot's own {@code stop()} has returned (the stop is on the
 * wire to its hardware).
 *
 * <p>The node must allow the calls' classes: build it with {@link RobotProtocol#forServer}.
 * Close the server to stop serving; the node and the robot stay open.
 *
 * <p><b>Who may drive it.</b> Callers must know the robot topic's password (their calls are
 * signed with it, and a call without it is refused), or reach the node over mutual TLS, which
 * lets in only peers with a certificate it trusts. Serving a robot to anyone who reaches the node
 * takes {@link #serveInsecure}, and is logged as a warning (docs/security.md).
 */
public final class RobotServer implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(RobotServer.class);

    private final MessagingNode node;
    private final Robot robot;
    private final String topic;
    private final MessageListener listener = this::onCall;
    /** The calls still running, by the correlation id of their request, for {@link RobotCall.Cancel}. */
    private final Map<UUID, CompletableFuture<Serializable>> running = new ConcurrentHashMap<>();

    private RobotServer(MessagingNode node, Robot robot) {
        this.node = node;
        this.robot = robot;
        this.topic = RobotProtocol.topic(robot.name());
    }

    /**
     * Starts serving to callers who know the password, or who reach the node over mutual TLS.
     *
     * @param node     the node callers reach (bound to the address they use)
     * @param robot    the robot
     * @param password the topic password callers must use; {@code null} only on a node with mutual TLS and no broker address
     * @return the server
     * @throws IllegalArgumentException naming the robot if there is no password and nothing else keeps strangers out
     */
    public static RobotServer serve(MessagingNode node, Robot robot, String password) {
        if (password == null && !onlyTlsPeers(node)) {
            throw new IllegalArgumentException("robot '" + robot.name() + "' would be served at " + node.boundAddresses()
                    + " to anyone who reaches it: give its callers a password (mw host --serve-password-file FILE), serve it over mutual TLS"
                    + " (tcp:// or rmi:// with TLS settings), or, for a lab that wants it, serve it insecurely (mw host --serve-insecure,"
                    + " RobotServer.serveInsecure)");
        }
        return start(node, robot, password);
    }

    /**
     * Starts serving to anyone who reaches the node, without a password, and says so in a warning:
     * for a closed lab network that wants it.
     *
     * @param node  the node callers reach
     * @param robot the robot
     * @return the server
     */
    public static RobotServer serveInsecure(MessagingNode node, Robot robot) {
        LOG.warn("serving robot '{}' WITHOUT A PASSWORD at {}: anyone who can reach these addresses can drive it", robot.name(), node.boundAddresses());
        return start(node, robot, null);
    }

    /** @return whether only peers with a certificate the node trusts can reach it: mutual TLS, and no broker (whose clients would reach it) */
    private static boolean onlyTlsPeers(MessagingNode node) {
        return node.settings().tlsSettings().isPresent() && node.boundAddresses().stream().noneMatch(a -> a.scheme().startsWith("mqtt")
                || a.scheme().equals("udp") || a.scheme().equals("multicast"));
    }

    private static RobotServer start(MessagingNode node, Robot robot, String password) {
        RobotServer server = new RobotServer(node, robot);
        node.answerTo(robot.name());
        node.addMessageListener(server.topic, password, server.listener);
        node.presence().addRobot(robot.name());
        LOG.info("serving robot '{}' at {}", robot.name(), node.boundAddresses());
        return server;
    }

    @Override
    public void close() {
        node.removeMessageListener(topic, listener);
        node.presence().removeRobot(robot.name());
    }

    private void onCall(Message m) {
        if (!(m.payload() instanceof RobotCall call)) {
            node.replyMessage(m, new RobotReply(null, new IllegalArgumentException("not a robot call: "
                    + (m.payload() == null ? "null" : m.payload().getClass().getName()))), "failed");
            return;
        }
        if (call instanceof RobotCall.Cancel cancel) {
            CompletableFuture<Serializable> target = running.get(cancel.call());
            boolean wasRunning = target != null && target.cancel(true);
            if (wasRunning) {
                LOG.info("robot '{}': a call of '{}' was cancelled by its caller (its wait ended early); its command ends", robot.name(), m.sender());
            }
            reply(m, call, wasRunning, null);
            return;
        }
        CompletableFuture<Serializable> done = run(call);
        if (!done.isDone()) {
            UUID id = m.correlationId();
            running.put(id, done);
            done.whenComplete((v, e) -> running.remove(id, done));
        }
        done.whenComplete((value, failure) -> reply(m, call, value, failure));
    }

    private CompletableFuture<Serializable> run(RobotCall call) {
        try {
            return call.run(robot);
        } catch (RuntimeException e) {
            return CompletableFuture.failedFuture(e);
        }
    }

    private void reply(Message m, RobotCall call, Serializable value, Throwable failure) {
        RobotReply reply = failure == null ? new RobotReply(value, null) : new RobotReply(null, RobotFailures.travelling(failure));
        try {
            node.replyMessage(m, reply, failure == null ? "ok" : "failed");
        } catch (RuntimeException e) {
            LOG.warn("robot '{}': cannot answer {} from '{}': {}", robot.name(), call, m.sender(), e.getMessage());
        }
    }
}
