package io.robomw.platform.brick;

import io.robomw.platform.link.Communicator;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * An exchange waits for the channel with a deadline: behind one that never ends it gives up with
 * an error naming the robot and the link, instead of blocking its thread (a program's sensor read,
 * the link's owner) for ever.
 */
class BrickChannelBusyTest {

    @Test
    void anExchangeBehindOneThatNeverEndsGivesUpNamingTheRobotAndTheLink() throws Exception {
        Communicator c = new Communicator(new ScriptedLink().named("silent link")); // takes every write, never answers
        c.open();
        BrickChannel channel = new BrickChannel("stuck-bot", c, Duration.ofMillis(100));
        channel.exchange((link, timeout) -> null); // answered once: later waits are the reply timeout's, not the first reply's

        CompletableFuture<Void> holding = new CompletableFuture<>();
        CountDownLatch release = new CountDownLatch(1);
        Thread holder = new Thread(() -> {
            try {
                channel.exchange((link, timeout) -> {
                    holding.complete(null);
                    try {
                        release.await(30, TimeUnit.SECONDS); // a driver stuck inside its exchange
                    } catch (InterruptedException e) {
                        Thread.currentThread().interrupt();
                    }
                    return null;
                });
            } catch (Exception e) {
                holding.completeExceptionally(e);
            }
        }, "holder");
        holder.start();
        holding.get(10, TimeUnit.SECONDS);

        ChannelBusyException busy = assertThrows(ChannelBusyException.class, () -> channel.exchange((link, timeout) -> "never run"));
        assertTrue(busy.getMessage().contains("robot 'stuck-bot'") && busy.getMessage().contains("silent link"), busy.getMessage());

        release.countDown();
        holder.join(10_000);
        assertEquals("run", channel.exchange((link, timeout) -> "run"), "the channel is free again");
    }
}
