package io.robomw.agents.messaging.robot;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.Robot;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.Serializable;
import java.util.concurrent.CompletableFuture;

/**
 * Serves a local {@link Robot} to remote callers ({@link RemoteRobot},
 * {@code Robots.remote("tcp://host:port/name")}): answers each {@link RobotCall} on the robot's
 * topic with a {@link RobotReply} once the robot has done it. Motions run asynchronously, so the
 * messaging thread is never held while a robot moves; concurrent callers follow the robot's own
 * rules (most recent motion wins).
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
        CompletableFuture<Serializable> done;
        try {
            done = call.run(robot);
        } catch (RuntimeException e) {
            done = CompletableFuture.failedFuture(e);
        }
        done.whenComplete((value, failure) -> {
            RobotReply reply = failure == null ? new RobotReply(value, null) : new RobotReply(null, RobotFailures.travelling(failure));
            try {
                node.replyMessage(m, reply, failure == null ? "ok" : "failed");
            } catch (RuntimeException e) {
                LOG.warn("robot '{}': cannot answer {} from '{}': {}", robot.name(), call, m.sender(), e.getMessage());
            }
        });
    }
}
