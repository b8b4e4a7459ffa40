package io.robomw.it.messaging;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;

import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicReference;

/**
 * {@link SharedMemoryIT}'s subscribers, in a JVM of their own: {@code ADDRESS K on|off COUNT}
 * starts K nodes connected to ADDRESS (shared memory on or off in their settings), each subscribed
 * to {@code scan}; prints {@code READY}. Each expects {@link #expected COUNT pairs}: a large payload
 * made from its index, then the index as an Integer, in that order; prints {@code DONE} once every
 * node has them all, or {@code BAD what} at the first one out of place. Ends when stdin closes.
 */
public final class SharedMemorySubscriber {

    private SharedMemorySubscriber() {
    }

    /**
     * @param i a payload's index
     * @return the large payload of that index: 100 KB, every fifth 1 MiB, filled from a seed of i
     */
    public static byte[] large(int i) {
        byte[] b = new byte[i % 5 == 4 ? 1 << 20 : 100_000];
        new java.util.Random(i).nextBytes(b);
        return b;
    }

    /**
     * @param args ADDRESS K on|off COUNT
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        String address = args[0];
        int k = Integer.parseInt(args[1]);
        MessagingSettings settings = MessagingSettings.defaults().withMaxFrameSize(2 << 20).withSharedMemory(args[2].equals("on"));
        int count = Integer.parseInt(args[3]);
        AtomicInteger complete = new AtomicInteger();
        AtomicReference<String> bad = new AtomicReference<>();
        List<MessagingNode> nodes = new ArrayList<>();
        for (int n = 0; n < k; n++) {
            int me = n;
            MessagingNode node = MessagingNode.builder("shm-sub-" + n).settings(settings).replayDirectory(null).connect(address).build();
            nodes.add(node);
            int[] next = {0};
            node.addMessageListener("scan", null, m -> {
                int at = next[0]++;
                int i = at / 2;
                boolean ok = at % 2 == 0 ? m.payload() instanceof byte[] b && Arrays.equals(b, large(i)) : Integer.valueOf(i).equals(m.payload());
                if (!ok && bad.compareAndSet(null, "node " + me + ": payload " + at + " is not the expected one")) {
                    out.println("BAD " + bad.get());
                }
                if (at + 1 == 2 * count && complete.incrementAndGet() == k && bad.get() == null) {
                    out.println("DONE");
                }
            });
            node.subscribeMessage("scan", null);
        }
        out.println("READY");
        while (System.in.read() >= 0) {
            // until the test closes stdin
        }
        nodes.forEach(MessagingNode::close);
    }
}
