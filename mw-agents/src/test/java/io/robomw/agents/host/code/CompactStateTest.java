package io.robomw.agents.host.code;

import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.api.Agent;
import io.robomw.testkit.Allocations;
import org.junit.jupiter.api.Test;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.Serializable;
import java.nio.charset.StandardCharsets;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The compact form of an agent's state ({@link StateCodec#writeCompact}): it reads back as the
 * agent, the standard form is still read, a class that differs from the writer's or is not allowed
 * is refused naming it, an unknown header is refused, and it costs less to read than the standard
 * form (measured in bytes allocated by this thread, the lever on the many-agents benchmark's tail).
 */
class CompactStateTest {

    private static final StateCodec CODEC = new StateCodec(List.of(), 1 << 20);

    private static ArchiveClassLoader agentCode() throws IOException {
        return new ArchiveClassLoader(new CodeSources().archiveOf(VisitorAgent.class), CompactStateTest.class.getClassLoader());
    }

    /** A visitor agent of the archive's own class, as a host has it, with three stops. */
    private static Agent agent(ClassLoader code) throws Exception {
        Agent a = (Agent) code.loadClass(VisitorAgent.class.getName()).getConstructor().newInstance();
        a.itinerary().addStop("rmi://127.0.0.1:1099/a").addStop("rmi://127.0.0.1:1100/b").addStop("rmi://127.0.0.1:1101/c");
        return a;
    }

    private static byte[] compact(Serializable value) throws IOException {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        CODEC.writeCompact(value, out);
        return out.toByteArray();
    }

    @Test
    void anAgentGoesToAHostBeforeTheCompactFormInTheFormEveryBuildReadsAndSuchAHostRefusesTheCompactOne() throws Exception {
        ArchiveClassLoader code = agentCode();
        Agent a = agent(code);
        ByteArrayOutputStream standard = new ByteArrayOutputStream();
        CODEC.writeAgent(a, standard, StateCodec.Form.STANDARD);
        assertArrayEquals(new byte[] {(byte) 0xAC, (byte) 0xED, 0x00, 0x05}, java.util.Arrays.copyOf(standard.toByteArray(), 4));
        assertArrayEquals(StateCodec.write(a), standard.toByteArray(), "Java serialization's own stream, as builds before the compact form wrote");
        ByteArrayOutputStream compact = new ByteArrayOutputStream();
        CODEC.writeAgent(a, compact, StateCodec.Form.COMPACT);
        assertArrayEquals(new byte[] {0x52, 0x4D, 0x00, 0x01}, java.util.Arrays.copyOf(compact.toByteArray(), 4), "to a host that reads it: compact");
        assertEquals(a.itinerary().stops(), CODEC.read(standard.toByteArray(), code, Agent.class).itinerary().stops());

        StateCodec before = new StateCodec(List.of(), 1 << 20, StateCodec.Form.STANDARD);
        ByteArrayOutputStream written = new ByteArrayOutputStream();
        before.writeAgent(a, written, StateCodec.Form.COMPACT);
        assertArrayEquals(standard.toByteArray(), written.toByteArray(), "a codec as builds before the compact form had writes the standard form only");
        StateRejectedException refused = assertThrows(StateRejectedException.class, () -> before.read(compact.toByteArray(), code, Agent.class));
        assertTrue(refused.getMessage().contains("invalid stream header: 524D0001"), "as those builds refused it: " + refused.getMessage());
        assertEquals(a.itinerary().stops(), before.read(standard.toByteArray(), code, Agent.class).itinerary().stops());
    }

    @Test
    void compactStateReadsBackAsTheAgentAndIsSmaller() throws Exception {
        ArchiveClassLoader code = agentCode();
        Agent a = agent(code);
        for (int i = 0; i < 3; i++) { // the pooled stream: the second and third are written by the same one
            byte[] bytes = compact(a);
            assertArrayEquals(new byte[] {0x52, 0x4D, 0x00, 0x01}, java.util.Arrays.copyOf(bytes, 4));
            Agent back = CODEC.read(bytes, code, Agent.class);
            assertEquals(a.getClass(), back.getClass());
            assertEquals(a.itinerary().stops(), back.itinerary().stops());
            assertTrue(bytes.length < StateCodec.write(a).length, bytes.length + " compact bytes against " + StateCodec.write(a).length);
        }
    }

    @Test
    void theStandardFormIsStillRead() throws Exception {
        ArchiveClassLoader code = agentCode();
        Agent a = agent(code);
        Agent back = CODEC.read(StateCodec.write(a), code, Agent.class);
        assertEquals(a.itinerary().stops(), back.itinerary().stops());
    }

    @Test
    void aClassThatDiffersFromTheWritersIsRefusedNamingIt() throws Exception {
        ArchiveClassLoader code = agentCode();
        byte[] bytes = compact(agent(code));
        byte[] name = VisitorAgent.class.getName().getBytes(StandardCharsets.UTF_8);
        int at = indexOf(bytes, name) + name.length; // the fingerprint follows the name
        bytes[at + 3] ^= 0x10;
        StateRejectedException e = assertThrows(StateRejectedException.class, () -> CODEC.read(bytes, code, Agent.class));
        assertTrue(e.getMessage().contains(VisitorAgent.class.getName()) && e.getMessage().contains("differs"), e.getMessage());
    }

    @Test
    void aClassNotAllowedIsRefusedNamingIt() throws Exception {
        ArchiveClassLoader code = agentCode();
        byte[] bytes = compact(new java.util.concurrent.atomic.AtomicLong(7)); // serializable, but neither the agent's code nor allowed
        StateRejectedException e = assertThrows(StateRejectedException.class, () -> CODEC.read(bytes, code, Serializable.class));
        assertTrue(e.getMessage().contains("java.util.concurrent.atomic.AtomicLong") && e.getMessage().contains("allow-list"), e.getMessage());
    }

    /**
     * Bad input never hurts: a compact state cut short, or with any one byte changed, is read back or refused with the
     * codec's one refusal ({@link StateRejectedException}), never another exception (the fuzz test's contract, here over
     * every byte of a real compact state, with every cut and three changes of each byte).
     */
    @Test
    void aDamagedCompactStateIsReadOrRefusedWithTheOneRefusal() throws Exception {
        ArchiveClassLoader code = agentCode();
        byte[] good = compact(agent(code));
        int refused = 0;
        for (int at = 0; at < good.length; at++) {
            refused += readOrRefused(java.util.Arrays.copyOf(good, at), code);
            for (int flip : new int[] {0x01, 0x80, 0xFF}) {
                byte[] bad = good.clone();
                bad[at] ^= (byte) flip;
                refused += readOrRefused(bad, code);
            }
        }
        assertTrue(refused >= good.length, "every cut at least is refused: " + refused + " refusals for " + good.length + " bytes");
    }

    /** @return 1 if the codec refused the bytes, 0 if it read them; fails the test on any other outcome */
    private static int readOrRefused(byte[] bytes, ClassLoader code) {
        try {
            CODEC.read(bytes, code, Serializable.class);
            return 0;
        } catch (StateRejectedException expected) {
            return 1;
        }
    }

    @Test
    void anUnknownHeaderIsRefusedNamingIt() throws Exception {
        ArchiveClassLoader code = agentCode();
        byte[] bytes = compact(agent(code));
        bytes[3] = 2; // a version this host does not know
        StateRejectedException e = assertThrows(StateRejectedException.class, () -> CODEC.read(bytes, code, Agent.class));
        assertTrue(e.getMessage().contains("524d 0002"), e.getMessage());
    }

    @Test
    void readingTheCompactFormAllocatesLessThanTheStandardOne() throws Exception {
        ArchiveClassLoader code = agentCode();
        Agent a = agent(code);
        byte[] compact = compact(a);
        byte[] standard = StateCodec.write(a);
        // warm both paths (class lookups, caches, the JIT's first compilations), then measure each over the same number of reads
        long c = 0;
        long s = 0;
        for (int round = 0; round < 3; round++) {
            c = allocatedBy(() -> CODEC.read(compact, code, Agent.class));
            s = allocatedBy(() -> CODEC.read(standard, code, Agent.class));
        }
        System.out.printf("reading the state: %d bytes allocated (compact), %d (standard)%n", c, s);
        assertTrue(c < 0.85 * s, "compact " + c + " bytes per read against standard " + s);
    }

    @Test
    void writingTheCompactFormAllocatesLessThanTheStandardOne() throws Exception {
        Agent a = agent(agentCode());
        ByteArrayOutputStream sink = new ByteArrayOutputStream(4096);
        long c = 0;
        long s = 0;
        for (int round = 0; round < 3; round++) {
            c = allocatedBy(() -> {
                sink.reset();
                CODEC.writeCompact(a, sink);
            });
            s = allocatedBy(() -> {
                sink.reset();
                StateCodec.write(a, sink);
            });
        }
        System.out.printf("writing the state: %d bytes allocated (compact), %d (standard)%n", c, s);
        assertTrue(c < 0.5 * s, "compact " + c + " bytes per write against standard " + s);
    }

    /** @return the median over 5 batches of the bytes a call of the step allocates */
    private static long allocatedBy(Allocations.Step step) throws Exception {
        long[] batches = new long[5];
        for (int b = 0; b < batches.length; b++) {
            batches[b] = Allocations.perCall(200, step);
        }
        java.util.Arrays.sort(batches);
        return batches[batches.length / 2];
    }

    private static int indexOf(byte[] in, byte[] what) {
        outer:
        for (int i = 0; i + what.length <= in.length; i++) {
            for (int j = 0; j < what.length; j++) {
                if (in[i + j] != what[j]) {
                    continue outer;
                }
            }
            return i;
        }
        throw new AssertionError("not found");
    }
}
