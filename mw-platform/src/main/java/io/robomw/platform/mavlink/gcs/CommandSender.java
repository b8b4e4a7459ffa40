package io.robomw.platform.mavlink.gcs;

import io.robomw.api.RobotException;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.MavResult;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.Payload;

import java.util.Locale;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.Consumer;

/**
 * Sends COMMAND_LONGs and matches their COMMAND_ACKs, as MAVSDK's command sender does
 * (mavlink.md §1.4): each command is sent again after {@value #TIMEOUT_NANOS} ns without an
 * answer, at most {@value #RETRIES} times, and fails after that; IN_PROGRESS answers hold it
 * (no resending) for {@value #IN_PROGRESS_NANOS} ns more each; ACCEPTED completes it; any other
 * result fails it naming the result. An ACK is taken only when addressed to this ground station
 * (its system and component) or to nobody (0). One command of a kind is pending at a time: a
 * newer one of the same id supersedes the older, which fails.
 *
 * <p>Thread-safe: {@link #send} from any thread; {@link #acknowledged} and {@link #tick} on the
 * link's thread.
 */
final class CommandSender {

    /** Time to wait for an ACK before sending again: 0.5 s (MAVSDK's DEFAULT_TIMEOUT_S). */
    static final long TIMEOUT_NANOS = 500_000_000L;
    /** Times a command is sent again: 3 (MAVSDK's DEFAULT_RETRIES): 2 s in all. */
    static final int RETRIES = 3;
    /** How long an IN_PROGRESS answer holds a command. */
    static final long IN_PROGRESS_NANOS = 3_000_000_000L;

    private final String robot;
    private final Consumer<Payload> out;
    private final int ourSystem;
    private final int ourComponent;
    private final Map<Integer, Pending> pending = new ConcurrentHashMap<>();

    private static final class Pending {
        final Payload payload;
        final CompletableFuture<Void> result = new CompletableFuture<>();
        volatile int sent;
        volatile long deadline;

        Pending(Payload payload, long deadline) {
            this.payload = payload;
            this.deadline = deadline;
        }
    }

    CommandSender(String robot, Consumer<Payload> out, int ourSystem, int ourComponent) {
        this.robot = robot;
        this.out = out;
        this.ourSystem = ourSystem;
        this.ourComponent = ourComponent;
    }

    /**
     * Sends a command.
     *
     * @param targetSystem    the vehicle's system id
     * @param targetComponent its component id
     * @param command         the command
     * @param now             the monotonic clock, ns
     * @param params          param1.. (up to 7; missing ones are 0)
     * @return completes when ACCEPTED; fails with a {@link RobotException} naming the command and
     *         the result, or the timeout
     */
    CompletableFuture<Void> send(int targetSystem, int targetComponent, MavCmd command, long now, double... params) {
        Payload p = Payload.of(Messages.CommandLong.MESSAGE)
                .set(Messages.CommandLong.TARGET_SYSTEM, targetSystem)
                .set(Messages.CommandLong.TARGET_COMPONENT, targetComponent)
                .set(Messages.CommandLong.COMMAND, command.code());
        var fields = new io.robomw.platform.mavlink.wire.Field[]{Messages.CommandLong.PARAM1, Messages.CommandLong.PARAM2,
                Messages.CommandLong.PARAM3, Messages.CommandLong.PARAM4, Messages.CommandLong.PARAM5, Messages.CommandLong.PARAM6,
                Messages.CommandLong.PARAM7};
        for (int i = 0; i < Math.min(7, params.length); i++) {
            p.set(fields[i], params[i]);
        }
        Pending next = new Pending(p, now + TIMEOUT_NANOS);
        Pending old = pending.put(command.code(), next);
        if (old != null) {
            old.result.completeExceptionally(new RobotException("robot '" + robot + "': command " + command + " was superseded by a newer one"));
        }
        out.accept(p);
        return next.result;
    }

    /**
     * A COMMAND_ACK came.
     *
     * @param ack its fields
     * @param now the clock
     */
    void acknowledged(Payload ack, long now) {
        long ts = ack.getLong(Messages.CommandAck.TARGET_SYSTEM);
        long tc = ack.getLong(Messages.CommandAck.TARGET_COMPONENT);
        if ((ts != 0 && ts != ourSystem) || (tc != 0 && tc != ourComponent)) {
            return;
        }
        int command = (int) ack.getLong(Messages.CommandAck.COMMAND);
        Pending p = pending.get(command);
        if (p == null) {
            return;
        }
        MavResult result = MavResult.find(ack.getLong(Messages.CommandAck.RESULT)).orElse(MavResult.FAILED);
        if (result == MavResult.IN_PROGRESS) {
            p.deadline = now + IN_PROGRESS_NANOS;
            p.sent = RETRIES; // answered: no more resending
            return;
        }
        pending.remove(command, p);
        if (result == MavResult.ACCEPTED) {
            p.result.complete(null);
        } else {
            p.result.completeExceptionally(new CommandRefusedException("robot '" + robot + "': the vehicle answered " + name(command) + " with "
                    + result, result));
        }
    }

    /**
     * Sends again what was not answered in time, and fails what was never answered.
     *
     * @param now the clock
     */
    void tick(long now) {
        for (Map.Entry<Integer, Pending> e : pending.entrySet()) {
            Pending p = e.getValue();
            if (now < p.deadline) {
                continue;
            }
            if (p.sent < RETRIES) {
                p.sent++;
                p.deadline = now + TIMEOUT_NANOS;
                out.accept(p.payload);
            } else if (pending.remove(e.getKey(), p)) {
                p.result.completeExceptionally(new RobotException(String.format(Locale.ROOT,
                        "robot '%s': the vehicle did not answer %s (sent %d times, %.1f s)", robot, name(e.getKey()), RETRIES + 1,
                        (RETRIES + 1) * TIMEOUT_NANOS / 1e9)));
            }
        }
    }

    /**
     * Fails every pending command (the link is lost or closing).
     *
     * @param why the reason
     */
    void failAll(RuntimeException why) {
        for (Map.Entry<Integer, Pending> e : pending.entrySet()) {
            if (pending.remove(e.getKey(), e.getValue())) {
                e.getValue().result.completeExceptionally(why);
            }
        }
    }

    private static String name(int command) {
        return MavCmd.find(command).map(Enum::name).orElse("command " + command);
    }
}
