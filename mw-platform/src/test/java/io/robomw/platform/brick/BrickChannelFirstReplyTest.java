package io.robomw.platform.brick;

import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkTimeoutException;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.concurrent.locks.LockSupport;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/**
 * A brick just connected may be slow to answer its first telegram (a Bluetooth link being set up,
 * an emulator's process only just started on a loaded host): the first exchange on a channel waits
 * {@link BrickChannel#FIRST_REPLY_TIMEOUT}, later ones only the reply timeout.
 */
class BrickChannelFirstReplyTest {

    /** A brick that answers every byte written with the same byte, {@code delayMillis} later. */
    private static final class SlowEcho implements Link {
        volatile long delayMillis;
        private long dueAt = Long.MAX_VALUE;
        private byte pending;
        private boolean hasPending;

        SlowEcho(long delayMillis) {
            this.delayMillis = delayMillis;
        }

        @Override
        public void open() {
        }

        @Override
        public boolean isOpen() {
            return true;
        }

        @Override
        public synchronized void write(byte[] data, int off, int len) {
            pending = data[off];
            hasPending = true;
            dueAt = System.nanoTime() + delayMillis * 1_000_000L;
        }

        @Override
        public int read(byte[] buf, int off, int len, Duration timeout) {
            long deadline = System.nanoTime() + timeout.toNanos();
            while (true) {
                synchronized (this) {
                    if (hasPending && System.nanoTime() >= dueAt) {
                        buf[off] = pending;
                        hasPending = false;
                        return 1;
                    }
                }
                long left = deadline - System.nanoTime();
                if (left <= 0) {
                    return 0;
                }
                LockSupport.parkNanos(Math.min(left, 1_000_000L));
            }
        }

        @Override
        public String describe() {
            return "slow echo";
        }

        @Override
        public void close() {
        }
    }

    private static byte[] ping(BrickChannel channel, byte b) throws IOException {
        return channel.exchange((c, timeout) -> {
            c.send(new byte[]{b});
            return c.receiveExactly(1, timeout);
        });
    }

    @Test
    void shouldGiveTheFirstExchangeMoreTimeThanTheReplyTimeout() throws Exception {
        SlowEcho brick = new SlowEcho(600);
        Communicator c = new Communicator(brick);
        c.open();
        BrickChannel channel = new BrickChannel("slow", c, Duration.ofMillis(200));
        assertArrayEquals(new byte[]{7}, ping(channel, (byte) 7), "the first answer, 600 ms late, is awaited");
        brick.delayMillis = 5;
        assertArrayEquals(new byte[]{8}, ping(channel, (byte) 8));
        brick.delayMillis = 600;
        assertThrows(LinkTimeoutException.class, () -> ping(channel, (byte) 9), "later answers wait only the reply timeout");
    }
}
