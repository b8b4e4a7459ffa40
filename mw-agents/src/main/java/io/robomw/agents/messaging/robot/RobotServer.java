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
     * Starts serving.
     *
     * @param node     the node callers reach (bound to the address they use)
     * @param robot    the robot
     * @param password the topic password callers must use, or {@code null} (then rely on TLS or a trusted network)
     * @return the server
     */
    public static RobotServer serve(MessagingNode node, Robot robot, String password) {
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
