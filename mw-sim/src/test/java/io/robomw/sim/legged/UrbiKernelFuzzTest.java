package io.robomw.sim.legged;

import com.code_intelligence.jazzer.junit.FuzzTest;
import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.platform.aibo.UrbiReply;
import io.robomw.platform.aibo.UrbiReplyDecoder;
import io.robomw.sim.emulator.aibo.AiboEmulator;

import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.OptionalDouble;

/**
 * Fuzz test of what the emulated Aibo's URBI server reads from a client (docs/fuzzing.md): any
 * bytes as what a client sends, submitted to a session of {@link UrbiKernel} as the emulator's
 * reader submits them, then the server stepped as the world steps it (20 steps of 10 ms; the dog
 * of {@code examples/robots/aibo.yaml}, a new one for each input). The server refuses nothing by
 * throwing: a statement it cannot parse or run gets an {@code !!!} line, and it serves on. So:
 * <ul>
 *   <li>the session is not closed (the kernel closes one only when it failed inside), and every
 *   statement the splitter or the parser refuses got an error line;</li>
 *   <li>every message, written as the emulator writes it ({@link AiboEmulator#line}), is read back
 *   by the Aibo driver's decoder as that one message (its tag one a client can send);</li>
 *   <li>the session's jobs stay within {@value UrbiKernel#MAX_JOBS};</li>
 *   <li>afterwards a valid statement gets its answer: on a new session always, and on the same
 *   session unless what the client sent still holds it (an unended statement, comment or binary
 *   value, or a sequential statement still running: the client's own doing).</li>
 * </ul>
 */
class UrbiKernelFuzzTest {

    private static final LeggedDrive DRIVE = new RobotDescriptionLoader()
            .load(Path.of("..", "examples", "robots", "aibo.yaml").toAbsolutePath().normalize()).leggedDrive().orElseThrow();
    private static final int STEPS = 20;
    private static final long STEP_NANOS = 10_000_000L;
    private static final String CHECK = "fuzzcheck: 1 + 2,\n";
    private static final String CHECK_TAG = "fuzzcheck";
    private static final String CHECK_ANSWER = "3.000000";

    /** One message of the server, as a session's sink hears it. */
    private record Message(String tag, UrbiKernel.Kind kind, String text) {
    }

    /** The dog and its server, stepped by hand. */
    private static final class Server {
        final Quadruped dog = new Quadruped(DRIVE, 1);
        long nanos;
        final UrbiKernel kernel = new UrbiKernel("fuzzdog", dog, Server::sensor, () -> nanos);

        static OptionalDouble sensor(String device) {
            if (AiboDevices.DISTANCE_MAX_MM.containsKey(device)) {
                return OptionalDouble.of(AiboDevices.DISTANCE_MAX_MM.get(device));
            }
            if (device.equals("accelZ")) {
                return OptionalDouble.of(9.81);
            }
            return AiboDevices.SENSORS.contains(device) ? OptionalDouble.of(0) : OptionalDouble.empty();
        }

        void step() {
            nanos += STEP_NANOS;
            dog.advance(STEP_NANOS / 1e9);
            kernel.step();
        }
    }

    @FuzzTest
    void urbiRequest(byte[] bytes) {
        Server server = new Server();
        List<Message> heard = new ArrayList<>();
        UrbiKernel.Session session = server.kernel.open("fuzz", (millis, tag, kind, text) -> heard.add(new Message(tag, kind, text)));
        session.submit(bytes, 0, bytes.length);
        for (int i = 0; i < STEPS; i++) {
            server.step();
            if (session.jobs() > UrbiKernel.MAX_JOBS) {
                throw new AssertionError("the session runs " + session.jobs() + " jobs, above " + UrbiKernel.MAX_JOBS);
            }
        }
        if (session.isClosed()) {
            throw new AssertionError("the server closed the session: " + heard);
        }
        int[] statements = statements(bytes);
        int refused = statements[1];
        long errors = heard.stream().filter(m -> m.kind() == UrbiKernel.Kind.ERROR).count();
        if (!session.holding() && statements[0] <= UrbiKernel.MAX_PENDING && errors < refused) {
            throw new AssertionError(refused + " statements cannot be parsed, but the server sent " + errors + " errors: " + heard);
        }
        for (Message m : heard) {
            readByTheDriver(m);
        }

        List<Message> other = new ArrayList<>();
        UrbiKernel.Session fresh = server.kernel.open("check", (millis, tag, kind, text) -> other.add(new Message(tag, kind, text)));
        fresh.submit(CHECK);
        server.step();
        if (!other.contains(new Message(CHECK_TAG, UrbiKernel.Kind.VALUE, CHECK_ANSWER))) {
            throw new AssertionError("a new session's '" + CHECK.strip() + "' was not answered: " + other);
        }

        session.submit("\n"); // ends a line comment, a string
        if (!session.midStatement() && !session.holding()) {
            heard.clear();
            session.submit(CHECK);
            server.step();
            if (!heard.contains(new Message(CHECK_TAG, UrbiKernel.Kind.VALUE, CHECK_ANSWER))
                    && !heard.contains(new Message(CHECK_TAG, UrbiKernel.Kind.ERROR, UrbiKernel.TOO_MANY_JOBS))) {
                throw new AssertionError("after the fuzzed bytes, '" + CHECK.strip() + "' was not answered: " + heard);
            }
        }
    }

    /** @return how many statements the bytes hold, and how many of them the splitter or the parser refuses */
    private static int[] statements(byte[] bytes) {
        int[] counts = {0, 0};
        new UrbiStatementSplitter().feed(bytes, 0, bytes.length, new UrbiStatementSplitter.Listener() {
            @Override
            public void statement(String text, char terminator) {
                counts[0]++;
                try {
                    UrbiParser.parse(text, terminator);
                } catch (UrbiParser.UrbiSyntaxException e) {
                    counts[1]++;
                }
            }

            @Override
            public void error(String message) {
                counts[0]++;
                counts[1]++;
            }
        });
        return counts;
    }

    /** The message as the emulator writes it must be read by the Aibo driver's decoder as that message. */
    private static void readByTheDriver(Message m) {
        byte[] line = AiboEmulator.line(1234, m.tag(), m.kind(), m.text());
        List<UrbiReply> replies = new ArrayList<>();
        List<String> malformed = new ArrayList<>();
        new UrbiReplyDecoder().feed(line, 0, line.length, new UrbiReplyDecoder.Listener() {
            @Override
            public void reply(UrbiReply reply) {
                replies.add(reply);
            }

            @Override
            public void malformed(String why, String excerpt) {
                malformed.add(why + ": " + excerpt);
            }
        });
        String text = m.text().replace('\n', ' ').replace('\r', ' ');
        UrbiReply.Kind kind = switch (m.kind()) {
            case VALUE -> UrbiReply.Kind.VALUE;
            case SYSTEM -> UrbiReply.Kind.SYSTEM;
            case ERROR -> UrbiReply.Kind.ERROR;
        };
        if (!malformed.isEmpty() || replies.size() != 1 || !replies.get(0).equals(new UrbiReply(1234, m.tag(), kind, text, null))) {
            throw new AssertionError("the server's message " + m + " is read by the driver as " + replies + " " + malformed);
        }
    }
}
