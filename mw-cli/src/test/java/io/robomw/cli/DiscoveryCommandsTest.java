package io.robomw.cli;

import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw nodes}, {@code mw topics} and {@code mw msg echo}: a publisher started by {@code mw msg pub}
 * announces itself on a discovery group bound to loopback (TTL 0, a port of this test's own), and
 * is found there: listed, its topic listed, and echoed with its rate without being given its address.
 */
class DiscoveryCommandsTest {

    private static int freeUdpPort() throws IOException {
        try (DatagramSocket s = new DatagramSocket(0, InetAddress.getLoopbackAddress())) {
            return s.getLocalPort();
        }
    }

    private static int freeTcpPort() throws IOException {
        try (ServerSocket s = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            return s.getLocalPort();
        }
    }

    @Test
    void aPublisherIsFoundListedAndEchoedWithItsRate() throws Exception {
        String group = "multicast://239.255.77.78:" + freeUdpPort() + "?interface=lo&ttl=0";
        String address = "tcp://127.0.0.1:" + freeTcpPort();
        CompletableFuture<CliRun> pub = CompletableFuture.supplyAsync(() -> CliRun.mw("msg", "pub", address, "chatter", "hi", "--name", "talker",
                "--count", "60", "--rate", "20", "--wait-subscribers", "1", "--wait-timeout", "60s", "--beacon", group));
        try {
            // The publisher's JVM starts beside this one: on a loaded machine its first beacon may come after a listing's
            // window, so the listing is asked again, as a user would, until the publisher is up.
            CliRun[] listed = new CliRun[1];
            Await.until("mw nodes lists the publisher", Duration.ofSeconds(60), () -> {
                listed[0] = CliRun.mw("nodes", "--beacon", group);
                return listed[0].out().contains("talker  " + address);
            }, () -> listed[0] == null ? "nothing yet" : listed[0].out() + listed[0].err());
            CliRun nodes = listed[0];
            assertEquals(0, nodes.status(), nodes.err());
            assertTrue(nodes.out().contains("1 node on " + group), nodes.out());

            CliRun topics = CliRun.mw("topics", "--beacon", group);
            assertTrue(topics.out().contains("chatter  published by talker; listened to by nobody"), topics.out());

            CliRun echo = CliRun.mw("msg", "echo", "chatter", "--beacon", group, "--count", "20", "--timeout", "60s", "--name", "listener");
            assertEquals(0, echo.status(), echo.err());
            assertTrue(echo.out().contains("echoing topic 'chatter' from " + address), echo.out());
            assertEquals(20, echo.out().split("\\[chatter] talker data: hi", -1).length - 1, echo.out());
            Matcher rate = Pattern.compile("rate ([0-9.]+) Hz: .* \\(20 messages\\)").matcher(echo.out());
            assertTrue(rate.find(), echo.out());
            double hz = Double.parseDouble(rate.group(1));
            assertTrue(hz > 10 && hz < 30, "about the publisher's 20 Hz: " + hz);
        } finally {
            CliRun done = pub.get(60, TimeUnit.SECONDS);
            assertEquals(0, done.status(), done.err());
        }
    }

    @Test
    void echoSaysWhenNobodyPublishesTheTopic() throws Exception {
        String group = "multicast://239.255.77.78:" + freeUdpPort() + "?interface=lo&ttl=0";
        CliRun echo = CliRun.mw("msg", "echo", "nothing", "--beacon", group, "--discover", "300ms");
        assertEquals(1, echo.status());
        assertTrue(echo.err().contains("no node announced on " + group + " publishes topic 'nothing'"), echo.err());
    }

    @Test
    void theRateIsTheMeanOverTheWindow() {
        RateMeter meter = new RateMeter(3);
        assertEquals("rate: no messages yet", meter.line());
        long t = 0;
        for (long gap : new long[] {900_000_000L, 100_000_000L, 100_000_000L, 100_000_000L}) {
            meter.arrived(t);
            t += gap;
        }
        meter.arrived(t);
        assertEquals("rate 10.00 Hz: min 0.100 s, max 0.100 s, std dev 0.0000 s, window 3 (5 messages)", meter.line());
    }
}
