package io.robomw.agents.messaging.robot;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Agency;
import io.robomw.api.Messaging;
import io.robomw.api.Capability;
import io.robomw.api.Futures;
import io.robomw.api.MessagingException;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.AgencyComponent;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.Serializable;
import java.time.Duration;
import java.util.EnumSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CancellationException;
import java.util.concurrent.CompletionException;

/**
 * A robot served by another process ({@link RobotServer}), reached through a messaging node.
 * {@code move}, {@code turn}, {@code getValue} and the other verbs run on the remote robot and
 * throw what a local call would: {@link UnsupportedActionException},
 * {@link io.robomw.api.CommandPreemptedException} and so on arrive as themselves (with the remote
 * stack trace, and the local call site as a suppressed exception). When the remote host does not
 * answer in time (the reply timeout, plus the motion's own duration) or the link closes, the call
 * fails with {@link RobotLinkException}, like a local robot whose link failed.
 *
 * <p>The verbs keep their contracts across the link: cancelling the future of a remote motion
 * (which a blocking verb does when its wait is interrupted or passes its deadline) ends the command
 * on the serving host, so an interrupted {@code move} does not drive on; {@link #stop()} returns once
 * the serving robot's own {@code stop()} has returned (the stop is on the wire to its hardware).
 *
 * <p>Messaging calls go through the local node, which is connected to the serving host's node:
 * publications reach that host's subscribers (its agents), and its publications reach this
 * program. Agents are sent through this program's own agency (an in-process home, as for a
 * local robot). Closing releases the link, the home and the node (if this robot made it); the
 * remote robot keeps running, and motions already started finish there. Thread-safe.
 */
public final class RemoteRobot implements Robot {

    private static final Logger LOG = LoggerFactory.getLogger(RemoteRobot.class);

    private final MessagingNode node;
    private final boolean ownsNode;
    private final AgencyComponent agency;
    private final String host;
    private final String password;
    private final String topic;
    private final RobotInfo info;

    /**
     * Connects and fetches the robot's description.
     *
     * @param node      the local node (its settings must come from {@link RobotProtocol#forClient})
     * @param ownsNode  whether closing this robot closes the node
     * @param host      the serving node's address, for example {@code tcp://127.0.0.1:7000}
     * @param robotName the robot's name there
     * @param password  the robot topic's password, or {@code null}
     * @param agency    how this program sends agents (closed with this robot)
     * @throws RobotLinkException if the robot does not answer
     */
    public RemoteRobot(MessagingNode node, boolean ownsNode, String host, String robotName, String password, AgencyComponent agency) {
        this.node = node;
        this.ownsNode = ownsNode;
        this.agency = agency;
        this.host = host;
        this.password = password;
        this.topic = RobotProtocol.topic(robotName);
        try {
            this.info = (RobotInfo) Futures.await(call(robotName, new RobotCall.Describe()), Futures.DEFAULT_TIMEOUT,
                    "describe robot '" + robotName + "' at " + host);
        } catch (RobotLinkException e) {
            throw notServed(robotName, e);
        }
    }

    /**
     * @return an error that says a robot is not served at the host, and which robots are, when the
     *         host refused the robot's topic; else the failure as it was
     */
    private RobotLinkException notServed(String robotName, RobotLinkException e) {
        String text = String.valueOf(e.getMessage());
        if (!text.contains("no listener for topic '" + topic + "'")) {
            return e;
        }
        String marker = "topics under '" + RobotProtocol.TOPIC_PREFIX + "' here: ";
        int at = text.indexOf(marker);
        List<String> served = at < 0 ? List.of()
                : java.util.Arrays.stream(text.substring(at + marker.length()).split("[,;]")).map(String::strip)
                        .filter(t -> t.startsWith(RobotProtocol.TOPIC_PREFIX)).map(t -> t.substring(RobotProtocol.TOPIC_PREFIX.length()).split("\\s")[0])
                        .toList();
        String example = served.isEmpty() || host.contains("?") ? "" : " (" + host + "/" + served.get(0) + ")";
        return new RobotLinkException("no robot '" + robotName + "' is served at " + host + (served.isEmpty() ? "; it serves none"
                : "; it serves " + String.join(", ", served) + example), e);
    }

    @Override
    public String name() {
        return info.name();
    }

    @Override
    public Set<Capability> capabilities() {
        return info.capabilities().isEmpty() ? Set.of() : Set.copyOf(EnumSet.copyOf(info.capabilities()));
    }

    @Override
    public List<SensorInfo> sensors() {
        return info.sensorInfos();
    }

    @Override
    public List<String> actions() {
        return List.copyOf(info.actions());
    }

    /** @return the address of the host serving it */
    public String host() {
        return host;
    }

    // ---- Motion ----

    @Override
    public CompletableFuture<Void> moveAsync(double distance, double speed) {
        return motion(call(new RobotCall.Move(distance, speed)));
    }

    @Override
    public CompletableFuture<Void> turnAsync(double radians, double speed) {
        return motion(call(new RobotCall.Turn(radians, speed)));
    }

    @Override
    public CompletableFuture<Void> arcAsync(double radius, double angle, double speed) {
        return motion(call(new RobotCall.Arc(radius, angle, speed)));
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        Futures.await(call(new RobotCall.Drive(linearSpeed, angularSpeed)), Futures.DEFAULT_TIMEOUT, "drive");
    }

    @Override
    public void stop() {
        Futures.await(call(new RobotCall.Stop()), Futures.DEFAULT_TIMEOUT, "stop()");
    }

    @Override
    public CompletableFuture<Void> changeAltitudeAsync(double metres, double speed) {
        return motion(call(new RobotCall.ChangeAltitude(metres, speed)));
    }

    @Override
    public CompletableFuture<Void> performAsync(String action, double... args) {
        return motion(call(new RobotCall.Perform(action, args.clone())));
    }

    // ---- Perception ----

    @Override
    public CompletableFuture<Double> getValueAsync(Position position, SensorType type, ReturnType returnType) {
        CompletableFuture<Serializable> read = call(new RobotCall.GetValue(position, type, returnType));
        return Futures.cancelling(read.thenApply(v -> (Double) v), read);
    }

    @Override
    public CompletableFuture<Double> getValueAsync(String sensorName, ReturnType returnType) {
        CompletableFuture<Serializable> read = call(new RobotCall.GetValueByName(sensorName, returnType));
        return Futures.cancelling(read.thenApply(v -> (Double) v), read);
    }

    @Override
    public Pose pose() {
        double[] p = (double[]) Futures.await(call(new RobotCall.GetPose()), Futures.DEFAULT_TIMEOUT, "pose()");
        return new Pose(p[0], p[1], p[2]);
    }

    @Override
    public void resetPose(Pose pose) {
        Futures.await(call(new RobotCall.ResetPose(pose.x(), pose.y(), pose.heading())), Futures.DEFAULT_TIMEOUT, "resetPose()");
    }

    /** @return the local messaging node, which this robot's messaging calls go to */
    @Override
    public Messaging messaging() {
        return node;
    }

    @Override
    public Agency agency() {
        return agency;
    }

    @Override
    public void close() {
        try {
            agency.close();
        } finally {
            if (ownsNode) {
                node.close();
            }
        }
    }

    @Override
    public String toString() {
        return "RemoteRobot[" + info.name() + " at " + host + "]";
    }

    private CompletableFuture<Serializable> call(RobotCall call) {
        return call(info.name(), call);
    }

    /** @return a motion call's future as the verb's, cancelling which cancels the call (and so the command on the serving host) */
    private static CompletableFuture<Void> motion(CompletableFuture<Serializable> call) {
        return Futures.cancelling(call.thenApply(v -> null), call);
    }

    /**
     * Sends a call and returns the future of its result. Cancelling that future (which a blocking
     * verb does when its wait ends early: interrupted, or past its deadline) sends a
     * {@link RobotCall.Cancel} for it, and the serving host cancels the robot's own future: the
     * command ends there, its motors brake.
     */
    private CompletableFuture<Serializable> call(String robotName, RobotCall call) {
        RobotException callSite = new RobotException("remote call " + call + " to robot '" + robotName + "' at " + host);
        Duration timeout = node.settings().replyTimeout().plus(call.expectedDuration());
        MessagingNode.Request request;
        try {
            request = node.startRequest(robotName, host, password, topic, call, RobotProtocol.CALL, timeout);
        } catch (MessagingException e) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + robotName + "' at " + host + " cannot be reached: " + e.getMessage(), e));
        }
        CompletableFuture<Serializable> result = request.reply().handle((m, e) -> {
            if (e != null) {
                Throwable cause = e instanceof CompletionException && e.getCause() != null ? e.getCause() : e;
                throw new RobotLinkException("robot '" + robotName + "' at " + host + " did not answer " + call + ": " + cause.getMessage(), cause);
            }
            if (!(m.payload() instanceof RobotReply r)) {
                throw new RobotLinkException("robot '" + robotName + "' at " + host + " answered " + call + " with "
                        + (m.payload() == null ? "nothing" : m.payload().getClass().getName()), null);
            }
            if (r.failure() != null) {
                r.failure().addSuppressed(callSite);
                if (r.failure() instanceof RuntimeException re) {
                    throw re;
                }
                throw new RobotException(r.failure().toString(), r.failure());
            }
            return r.value();
        });
        result.whenComplete((v, e) -> {
            if (e instanceof CancellationException) {
                cancelRemote(robotName, call, request);
            }
        });
        return result;
    }

    /** Tells the serving host to end a call whose caller stopped waiting; its reply is not awaited. */
    private void cancelRemote(String robotName, RobotCall call, MessagingNode.Request request) {
        request.reply().cancel(false);
        try {
            node.startRequest(robotName, host, password, topic, new RobotCall.Cancel(request.correlationId()), RobotProtocol.CALL,
                    node.settings().replyTimeout()).reply().whenComplete((m, e) -> {
                        if (e != null) {
                            LOG.warn("robot '{}' at {}: the cancel of {} was not answered ({}); the command may go on there", robotName, host, call,
                                    e.getMessage());
                        }
                    });
        } catch (MessagingException e) {
            LOG.warn("robot '{}' at {}: cannot cancel {} there ({}); the command may go on there", robotName, host, call, e.getMessage());
        }
    }
}
