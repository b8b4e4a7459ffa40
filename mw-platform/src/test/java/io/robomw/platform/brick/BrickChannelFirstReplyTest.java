package io.robomw.platform.brick;

import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.LinkTimeoutException;
import io.robomw.platform.testkit.Answer;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.concurrent.atomic.AtomicLong;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/**
 * A brick just connected may be slow to answer its first telegram (a Bluetooth link being set up,
 * an emulator's process only just started on a loaded host): the first exchange on a channel waits
 * {@link BrickChannel#FIRST_REPLY_TIMEOUT}, later ones only the reply timeout.
 */
class BrickChannelFirstReplyTest {

    /** How late the brick answers. */
    private final AtomicLong delayMillis = new AtomicLong();
    /** A brick that answers every byte written with the same byte, {@link #delayMillis} later. */
    private final ScriptedLink brick = new ScriptedLink().named("slow echo")
            .answeringWith(written -> Answer.of(new byte[]{written[0]}).after(Duration.ofMillis(delayMillis.get())));

    private static byte[] ping(BrickChannel channel, byte b) throws IOException {
        return channel.exchange((c, timeout) -> {
            c.send(new byte[]{b});
            return c.receiveExactly(1, timeout);
        });
    }

    @Test
    void shouldGiveTheFirstExchangeMoreTimeThanTheReplyTimeout() throws Exception {
        delayMillis.set(600);
        Communicator c = new Communicator(brick);
        c.open();
        BrickChannel channel = new BrickChannel("slow", c, Duration.ofMillis(200));
        assertArrayEquals(new byte[]{7}, ping(channel, (byte) 7), "the first answer, 600 ms late, is awaited");
        delayMillis.set(5);
        assertArrayEquals(new byte[]{8}, ping(channel, (byte) 8));
        delayMillis.set(600);
        assertThrows(LinkTimeoutException.class, () -> ping(channel, (byte) 9), "later answers wait only the reply timeout");
    }
}
