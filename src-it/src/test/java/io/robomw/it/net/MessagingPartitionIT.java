package io.robomw.it.net;

import io.robomw.it.messaging.Peer;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.parallel.Execution;
import org.junit.jupiter.api.parallel.ExecutionMode;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.time.Duration;
import java.util.List;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Request/reply and publish/subscribe between messaging nodes ({@link Peer}s) in network
 * namespaces while the network between them fails, directly over TCP and through an MQTT broker
 * ({@code mw broker}) cut off from one of them. What each transport queues, refuses and loses is
 * asserted here as docs/messaging.md states it ("Through a partition"); figures go to
 * {@code target/network-figures.md}.
 */
@Execution(ExecutionMode.CONCURRENT)
class MessagingPartitionIT {

    private static final Duration WAIT = Duration.ofSeconds(90);

    private NetLab lab;

    @AfterEach
    void removeLab() {
        if (lab != null) {
            lab.close();
        }
    }

    private static LabProcess peer(LabHost at, String name, String... jvm) {
        try {
            LabProcess p = at.java(at.lab().tag() + "-" + name, List.of(jvm), Peer.class.getName(), name);
            p.expect("READY", LabHost.START);
            return p;
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private static String awaitLog(LabProcess p, String what, String regex) {
        Pattern pattern = Pattern.compile(regex);
        String[] found = new String[1];
        Await.until(what, WAIT, () -> {
            try {
                found[0] = p.log().lines().filter(l -> pattern.matcher(l).find()).findFirst().orElse(null);
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
            return found[0] != null;
        });
        return found[0];
    }

    @Test
    void overTcpAShortCutDelaysButLosesNothingAndALongOneClosesTheLinkWhichComesBackWithoutWhatWasPublishedMeanwhile() throws Exception {
        lab = NetLab.open("tcp");
        LabHost xs = lab.host("x");
        LabHost ys = lab.host("y");
        // idle timeout 12 s: keep-alives every 4 s; a link that carried no frame for 12 s is closed
        LabProcess x = peer(xs, "x", "-Dpeer.idleMillis=12000");
        LabProcess y = peer(ys, "y", "-Dpeer.idleMillis=12000");
        String xAddress = "tcp://" + xs.ip() + ":7000";
        x.ask("bind " + xAddress, "BOUND", WAIT);
        x.ask("echo cmd -", "OK", WAIT);
        y.ask("connect " + xAddress, "OK", WAIT);
        y.ask("subscribe news -", "OK", WAIT);
        assertEquals("SUBS 1", x.ask("waitsubs news 1 60", "SUBS", WAIT));
        assertEquals("REPLY hello", y.ask("request " + xAddress + " x cmd hello -", "REPLY", WAIT));

        // A short cut (less than the idle timeout): TCP keeps what was written and delivers it after.
        lab.partition(xs, ys);
        long cut = System.nanoTime();
        x.ask("publish news 0 20 -", "PUBLISHED 20", WAIT);
        String during = y.ask("request " + xAddress + " x cmd during -", "FAILED", WAIT); // waits its 5 s reply timeout
        lab.heal();
        long healed = System.nanoTime();
        assertTrue(during.contains("cmd") && during.contains(xAddress), "the time-out names the topic and the host: " + during);
        assertEquals("COUNT news 20 ordered=true", y.ask("await news 20 60", "COUNT", WAIT), "nothing published during the short cut was lost");
        long delivered = System.nanoTime();
        assertEquals("REPLY again", y.ask("request " + xAddress + " x cmd again -", "REPLY", WAIT));

        // A long cut: both ends close the silent link after the idle timeout; y connects again once it heals.
        lab.partition(xs, ys);
        long longCut = System.nanoTime();
        String closed = awaitLog(x, "x closes the silent link", "(idle|no frame|TIMED_OUT|timed out).*" + Pattern.quote(ys.ip()) + "|"
                + Pattern.quote(ys.ip()) + ".*(idle|no frame|TIMED_OUT|timed out)");
        Await.until("the subscription went with the link", WAIT, () -> x.ask("waitsubs news 0 0", "SUBS", WAIT).equals("SUBS 0"));
        x.ask("publish news 20 20 -", "PUBLISHED 20", WAIT); // to nobody: y's link is gone
        lab.heal();
        long healed2 = System.nanoTime();
        assertEquals("SUBS 1", x.ask("waitsubs news 1 60", "SUBS", WAIT), "y connected again and subscribed again");
        long back = System.nanoTime();
        x.ask("publish news 40 20 -", "PUBLISHED 20", WAIT);
        Await.until("y has the publications after it came back", WAIT, () -> y.ask("count news", "COUNT", WAIT).startsWith("COUNT news 40 "));
        assertEquals("DISTINCT news 40 of 40", y.ask("distinct news", "DISTINCT", WAIT), "none twice; 20-39, published while the link was down, never came");
        assertFalse(closed.contains("127.0.0.1"), "the log names y's address: " + closed);
        NetFigures.record("TCP, request/reply and pub/sub through a cut (idle timeout 12 s)",
                String.format("short cut %.1f s: request timed out (5 s), 20 publications delivered in order %.1f s after healing; long cut %.1f s: link closed,"
                        + " 20 publications to nobody, y subscribed again %.1f s after healing", (healed - cut) / 1e9, (delivered - healed) / 1e9,
                        (healed2 - longCut) / 1e9, (back - healed2) / 1e9));
    }

    @Test
    void throughABrokerCutOffFromOneNodeAPersistentSessionGetsWhatWasPublishedAndSendsWhatItQueued() throws Exception {
        lab = NetLab.open("mqtt");
        LabHost bs = lab.host("broker");
        LabHost xs = lab.host("x");
        LabHost ys = lab.host("y");
        // mw broker lets in only its user (issue 37): its credentials go to a file the nodes are told of
        java.nio.file.Path credentials = java.nio.file.Files.createTempDirectory("mqtt-lab").resolve("broker.credentials");
        LabProcess broker = bs.mw("mqtt-broker", List.of("-Xmx256m"), "broker", "--bind", bs.ip(), "--port", "1883", "--credentials", credentials.toString());
        broker.expect("mqtt broker ready at", LabHost.START);
        String at = "mqtt://" + bs.ip() + ":1883";
        String user = "credentials=" + credentials;
        LabProcess x = peer(xs, "x");
        LabProcess y = peer(ys, "y");
        x.ask("echo cmd -", "OK", WAIT);
        x.ask("subscribe ynews -", "OK", WAIT);
        x.ask("bind " + at + "?" + user + "&keep-alive=2", "BOUND", WAIT);
        y.ask("subscribe news -", "OK", WAIT);
        y.ask("bind " + at + "?" + user + "&session-expiry=600&keep-alive=2", "BOUND", WAIT);
        assertEquals("REPLY hello", y.ask("request " + at + " x cmd hello -", "REPLY", WAIT));

        lab.partition(bs, ys);
        long cut = System.nanoTime();
        String lost = awaitLog(y, "y takes the broker as lost", "lost broker");
        x.ask("publish news 0 50 -", "PUBLISHED 50", WAIT); // the broker keeps them for y's session
        y.ask("publish ynews 0 10 -", "PUBLISHED 10", WAIT); // queued at y while the broker is away
        String during = y.ask("request " + at + " x cmd during -", "FAILED", WAIT);
        lab.heal();
        long healed = System.nanoTime();
        assertEquals("COUNT news 50 ordered=true", y.ask("await news 50 60", "COUNT", WAIT), "the broker kept what was published for y, in order");
        assertEquals("COUNT ynews 10 ordered=true", x.ask("await ynews 10 60", "COUNT", WAIT), "y sent what it queued once the broker was back");
        long delivered = System.nanoTime();
        assertEquals("REPLY again", y.ask("request " + at + " x cmd again -", "REPLY", WAIT));
        assertEquals("DISTINCT news 50 of 50", y.ask("distinct news", "DISTINCT", WAIT));
        assertTrue(lost.contains(bs.ip()), "y's log names the broker's address: " + lost);
        assertTrue(during.contains("cmd"), during);
        NetFigures.record("MQTT (mw broker), the broker cut off from node y (persistent session, keep-alive 2 s)",
                String.format("cut %.1f s: y's request timed out; 50 publications kept by the broker and 10 queued at y, all delivered in order %.1f s after"
                        + " healing", (healed - cut) / 1e9, (delivered - healed) / 1e9));
    }

    @Test
    void requestReplyThroughADelayedLinkTakesTheDelayAndAReplyLaterThanTheTimeoutIsReportedAsMissing() throws Exception {
        lab = NetLab.open("delay");
        LabHost xs = lab.host("x");
        LabHost rs = lab.host("relay");
        LabHost ys = lab.host("y");
        LabProcess x = peer(xs, "x");
        x.ask("bind tcp://" + xs.ip() + ":7000", "BOUND", WAIT);
        x.ask("echo cmd -", "OK", WAIT);
        // 300 ms each way on port 7000, 3 s each way on port 7001 (more than the request's 5 s reply timeout, both ways)
        rs.java("delay-relay", DelayRelay.class.getName(), "300", rs.ip(), "7000=" + xs.ip() + ":7000").expect("READY", LabHost.START);
        rs.java("delay-relay-slow", DelayRelay.class.getName(), "3000", rs.ip(), "7001=" + xs.ip() + ":7000").expect("READY", LabHost.START);
        LabProcess y = peer(ys, "y");
        String near = "tcp://" + rs.ip() + ":7000";
        assertEquals("REPLY warm", y.ask("request " + near + " x cmd warm -", "REPLY", WAIT)); // the connection is made
        long t0 = System.nanoTime();
        assertEquals("REPLY hello", y.ask("request " + near + " x cmd hello -", "REPLY", WAIT));
        double rtt = (System.nanoTime() - t0) / 1e9;
        assertTrue(rtt >= 0.6, "the round trip took at least the relay's 2 x 300 ms: " + rtt + " s");
        String far = "tcp://" + rs.ip() + ":7001";
        String late = y.ask("request " + far + " x cmd late -", "FAILED", WAIT);
        assertTrue(late.contains("on topic 'cmd' from " + far + " within PT5S"), "the time-out names the topic, the host and the timeout: " + late);
        NetFigures.record("TCP request/reply through a user-space delay relay",
                String.format("300 ms each way: round trip %.2f s (2 x 0.30 s of it the relay's); 3 s each way: no reply within the 5 s timeout, reported", rtt));
    }
}
