package io.robomw.agents.host.trip;

import io.robomw.api.Agent;

import java.util.ArrayList;
import java.util.Random;

/**
 * Test agent for reused transfer buffers: carries a payload whose size changes at every stop (from
 * a list of sizes) and whose bytes are drawn from a seed of its own; at each stop it checks that
 * the payload it arrived with is exactly the one it left with (length and every byte), then makes
 * the next one. Brings home one line per stop: "host size ok" or what was wrong.
 */
public class ResizingAgent extends Agent {

    private static final long serialVersionUID = 1L;

    private final long seed;
    private final int[] sizes;
    private int stop;
    private byte[] payload;
    private final ArrayList<String> log = new ArrayList<>();

    /**
     * @param seed  this agent's own byte stream (different agents, different bytes)
     * @param sizes the payload size it leaves with from each stop, the first from its home
     */
    public ResizingAgent(long seed, int... sizes) {
        this.seed = seed;
        this.sizes = sizes.clone();
        this.payload = bytes(seed, 0, sizes[0]);
    }

    private static byte[] bytes(long seed, int stop, int size) {
        byte[] b = new byte[size];
        new Random(seed * 1_000_003L + stop).nextBytes(b);
        return b;
    }

    @Override
    public void run() {
        byte[] expected = bytes(seed, stop, sizes[stop]);
        String verdict = java.util.Arrays.equals(expected, payload) ? "ok"
                : "CORRUPT (arrived with " + payload.length + " bytes, left with " + expected.length + ")";
        log.add(context().hostName() + " " + payload.length + " " + verdict);
        stop++;
        payload = bytes(seed, stop, sizes[Math.min(stop, sizes.length - 1)]);
        context().setResult(new ArrayList<>(log));
    }
}
