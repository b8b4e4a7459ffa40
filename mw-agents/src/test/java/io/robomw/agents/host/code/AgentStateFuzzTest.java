package io.robomw.agents.host.code;

import com.code_intelligence.jazzer.junit.FuzzTest;
import io.robomw.agents.host.trip.VisitorAgent;

import java.io.IOException;
import java.io.Serializable;
import java.io.UncheckedIOException;
import java.util.List;

/**
 * Fuzz test of the state streams a host reads from its peers (docs/fuzzing.md): an agent's state,
 * reports and results through {@link StateCodec}'s filter, with the agent's own code in an
 * archive's class loader as a host has it (so {@code Itinerary.readObject} and the agent's own
 * fields are reached). The only refusal allowed is {@link StateRejectedException}.
 */
class AgentStateFuzzTest {

    private static final StateCodec CODEC = new StateCodec(List.of(), 1 << 20);
    private static final ArchiveClassLoader AGENT_CODE;

    static {
        try {
            AGENT_CODE = new ArchiveClassLoader(new CodeSources().archiveOf(VisitorAgent.class), AgentStateFuzzTest.class.getClassLoader());
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    @FuzzTest
    void state(byte[] input) {
        try {
            CODEC.read(input, AGENT_CODE, Serializable.class);
        } catch (StateRejectedException refused) {
            // the documented refusal
        }
    }
}
