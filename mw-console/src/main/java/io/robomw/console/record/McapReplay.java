package io.robomw.console.record;

import io.robomw.console.mcap.McapReader;
import io.robomw.console.mcap.McapRecord;
import io.robomw.console.observe.HostView;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.BufferedInputStream;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.HashMap;
import java.util.Map;
import java.util.function.BooleanSupplier;

/**
 * Plays a recording back: reads its messages in file order (the order they were recorded), turns
 * each into the observation it was made from ({@link RecordingCodec}), and hands it to an observer
 * at the pace it was recorded, times a speed ({@code 0} = as fast as possible). Observations are
 * re-stamped onto the replay's clock (a message recorded {@code d} after the first one is stamped
 * the replay's start plus {@code d / speed}), so the console ages them as if they were live.
 * Messages on topics it does not know (another program's) are skipped. A truncated recording
 * (its recorder was killed) is played up to its last whole chunk.
 */
public final class McapReplay {

    private static final Logger LOG = LoggerFactory.getLogger(McapReplay.class);

    /**
     * What was played.
     *
     * @param messages        messages in the file
     * @param observations    observations handed on
     * @param recordedSeconds time between the first and last message
     * @param truncated       whether the file stopped before its footer
     */
    public record Played(long messages, long observations, double recordedSeconds, boolean truncated) {
    }

    private McapReplay() {
    }

    /**
     * Plays a recording.
     *
     * @param file     the .mcap file
     * @param observer who is told
     * @param speed    recorded seconds per second; 0 for as fast as possible
     * @param stop     checked between messages: true ends the replay early
     * @return what was played
     * @throws IOException if the file cannot be read or is not a recording (the message says where)
     */
    public static Played play(Path file, Observer observer, double speed, BooleanSupplier stop) throws IOException {
        return play(file, observer, o -> { }, speed, stop);
    }

    /**
     * Plays a recording to two observers at once: one on the replay's clock (as
     * {@link #play(Path, Observer, double, BooleanSupplier)}), and one that gets each observation
     * with the times it was recorded at, at the same moment (the live Foxglove WebSocket, which
     * tells its clients the recorded time).
     *
     * @param file       the .mcap file
     * @param observer   who is told, on the replay's clock
     * @param asRecorded who is told, in recorded time
     * @param speed      recorded seconds per second; 0 for as fast as possible
     * @param stop       checked between messages: true ends the replay early
     * @return what was played
     * @throws IOException if the file cannot be read or is not a recording (the message says where)
     */
    public static Played play(Path file, Observer observer, Observer asRecorded, double speed, BooleanSupplier stop) throws IOException {
        if (!(speed >= 0) || Double.isInfinite(speed)) {
            throw new IllegalArgumentException("replay speed must be a number >= 0 (0 = as fast as possible), got " + speed);
        }
        Map<Integer, String> schemaNames = new HashMap<>();
        Map<Integer, McapRecord.Channel> channels = new HashMap<>();
        long messages = 0;
        long observations = 0;
        long first = -1;
        long last = 0;
        long wallStart = System.currentTimeMillis() * 1_000_000L;
        long nanoStart = System.nanoTime();
        try (McapReader reader = new McapReader(new BufferedInputStream(Files.newInputStream(file), 1 << 16), file.toString(),
                McapReader.Options.DEFAULT.tolerant())) {
            for (McapRecord r; (r = reader.next()) != null && !stop.getAsBoolean(); ) {
                if (r instanceof McapRecord.Schema s) {
                    schemaNames.put(s.id(), s.name());
                } else if (r instanceof McapRecord.Channel c) {
                    channels.put(c.id(), c);
                } else if (r instanceof McapRecord.Message m) {
                    messages++;
                    McapRecord.Channel c = channels.get(m.channelId());
                    if (c == null) {
                        throw new IOException(file + ": a message on channel " + m.channelId() + " comes before that channel's record");
                    }
                    Observation o;
                    try {
                        o = RecordingCodec.decode(c.topic(), schemaNames.getOrDefault(c.schemaId(), ""), m.data(), m.logTime());
                    } catch (IOException e) {
                        throw new IOException(file + ": " + e.getMessage() + " (log time " + m.logTime() + ")", e);
                    }
                    if (o == null) {
                        continue;
                    }
                    if (first < 0) {
                        first = m.logTime();
                    }
                    last = Math.max(last, m.logTime());
                    double offsetNanos = (m.logTime() - first) / (speed == 0 ? 1 : speed);
                    if (speed > 0) {
                        waitUntil(nanoStart + (long) offsetNanos, stop);
                    }
                    long shift = wallStart + (long) (speed == 0 ? 0 : offsetNanos) - m.logTime();
                    asRecorded.observe(o);
                    observer.observe(restamped(o, shift, first, speed, wallStart));
                    observations++;
                }
            }
            if (reader.truncated()) {
                LOG.warn("{} ends before its footer (its recorder was killed?): played the {} messages before", file, messages);
            }
            return new Played(messages, observations, first < 0 ? 0 : (last - first) / 1e9, reader.truncated());
        }
    }

    private static void waitUntil(long nanoDeadline, BooleanSupplier stop) {
        while (!stop.getAsBoolean()) {
            long left = nanoDeadline - System.nanoTime();
            if (left <= 0) {
                return;
            }
            // Waiting for the recorded moment to come: this is the replay's pace, not a wait for a condition.
            java.util.concurrent.locks.LockSupport.parkNanos(Math.min(left, 50_000_000L));
        }
    }

    /** Moves an observation's times onto the replay's clock. */
    private static Observation restamped(Observation o, long shift, long first, double speed, long wallStart) {
        long t = o.timeNanos() + shift;
        if (o instanceof Observation.World w) {
            return new Observation.World(t, w.map());
        } else if (o instanceof Observation.RobotPose p) {
            return new Observation.RobotPose(t, p.robot(), p.x(), p.y(), p.z(), p.heading(), p.truth());
        } else if (o instanceof Observation.SensorReading s) {
            return new Observation.SensorReading(t, s.robot(), s.sensor(), s.value(), s.unit());
        } else if (o instanceof Observation.RobotCommand c) {
            return new Observation.RobotCommand(t, c.robot(), c.verb(), c.args());
        } else if (o instanceof Observation.RobotStatus s) {
            return new Observation.RobotStatus(t, s.robot(), s.source(), s.reachable(), s.detail());
        } else if (o instanceof Observation.HostSeen h) {
            HostView v = h.host();
            long contact = v.lastContactNanos() == 0 ? 0
                    : wallStart + (long) ((v.lastContactNanos() - first) / (speed == 0 ? Double.POSITIVE_INFINITY : speed));
            return new Observation.HostSeen(t, new HostView(v.address(), v.name(), v.up(), v.robot(), v.agents(), v.owed(), v.error(),
                    speed == 0 ? t : contact));
        } else if (o instanceof Observation.AgentEvent e) {
            return new Observation.AgentEvent(t, e.agent(), e.agentClass(), e.kind(), e.host(), e.detail());
        } else if (o instanceof Observation.TopicMessage m) {
            return new Observation.TopicMessage(t, m.topic(), m.text());
        }
        return o;
    }
}
