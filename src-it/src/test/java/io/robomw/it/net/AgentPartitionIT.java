package io.robomw.it.net;

import io.robomw.it.AtOnce;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.parallel.Execution;
import org.junit.jupiter.api.parallel.ExecutionMode;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Agents between hosts in network namespaces ({@link NetLab}) while the network fails: the next
 * host cut off while an agent waits to hop (for less, then for more than its itinerary's
 * patience), the home cut off while reports and results are owed, 20 % of the packets lost for a
 * whole trip of clones, a durable host killed during a partition. Each asserts that no agent, no
 * report and no result is lost or duplicated and no stop runs twice; the figures go to
 * {@code target/network-figures.md} (and docs/reliability.md).
 *
 * <p>Three JVMs at most: the home (a {@link TripHome}) and two {@code mw host}s, each in its
 * namespace, with 2 s call timeouts (so a host cut off costs a hop attempt 2 s, not 30) and 2 s
 * at most between tries to deliver to a home.
 */
@Execution(ExecutionMode.CONCURRENT)
class AgentPartitionIT {

    private static final Duration TRIP = Duration.ofMinutes(3);
    private static final Pattern RETRY_LINE = Pattern.compile("agent (\\S+) cannot reach its next stop (\\S+) \\(attempt (\\d+) of (\\d+)\\): (.*)");

    @TempDir
    Path dir;
    private NetLab lab;
    private LabHost homeNs;
    private LabHost aNs;
    private LabHost bNs;
    private LabProcess a;
    private LabProcess b;
    private TripLog home;
    private Path keyFile;

    @AfterEach
    void removeLab() {
        if (lab != null) {
            lab.close();
        }
    }

    private void start(String tag, boolean durableA) throws IOException {
        lab = NetLab.open(tag);
        homeNs = lab.host("home");
        aNs = lab.host("a");
        bNs = lab.host("b");
        keyFile = dir.resolve("cluster.key");
        Files.writeString(keyFile, "network lab cluster\n");
        // The three JVMs start at once (each in its namespace; none needs another to start); the lab stops whichever started.
        List<LabProcess> started = AtOnce.all(List.of(
                new AtOnce.Step<>("starting host a", () -> startA(durableA)),
                new AtOnce.Step<>("starting host b", () -> bNs.agentHost("b", keyFile, hostOptions())),
                new AtOnce.Step<>("starting the home", () -> {
                    LabProcess p = homeNs.java(tag + "-home", TripHome.class.getName(), "home", homeNs.ip(), keyFile.toString());
                    p.expect("READY", LabHost.START);
                    return p;
                })), LabHost.START.plusSeconds(30), p -> { });
        a = started.get(0);
        b = started.get(1);
        home = new TripLog(started.get(2));
    }

    private LabProcess startA(boolean durable) throws IOException {
        String[] opts = hostOptions();
        if (durable) {
            opts = java.util.stream.Stream.concat(java.util.Arrays.stream(opts), java.util.stream.Stream.of("--store", dir.resolve("a-store").toString()))
                    .toArray(String[]::new);
        }
        return aNs.agentHost("a", keyFile, opts);
    }

    private static String[] hostOptions() {
        return new String[] {"--call-timeout", "2s", "--owed-max-backoff", "2s"};
    }

    private String aAddress() {
        return aNs.rmi("a");
    }

    private String bAddress() {
        return bNs.rmi("b");
    }

    /** Waits until host a's log shows {@code n} failed attempts of agent {@code id} to reach b. */
    private List<String> awaitFailedAttempts(LabProcess host, String id, int n) {
        List<String>[] lines = new List[1];
        Await.until(n + " failed attempts of agent " + id + " to reach " + bAddress(), TRIP, () -> {
            lines[0] = retryLines(host, id);
            return lines[0].size() >= n;
        });
        return lines[0];
    }

    private static List<String> retryLines(LabProcess host, String id) {
        try {
            return host.log().lines().filter(l -> l.contains("agent " + id + " cannot reach its next stop")).toList();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    @Test
    void nextHostCutOffForLessThanThePatienceIsVisitedOnceItIsBack() throws Exception {
        start("nshort", false);
        lab.isolate(bNs);
        // Patience: 1 + 20 attempts, 1 s apart, each up to the 2 s call timeout: about a minute.
        String id = home.send("trip 500 20 1000 " + aAddress() + "," + bAddress() + "," + aAddress(), 1, TRIP).get(0);
        long cut = System.nanoTime();
        List<String> failed = awaitFailedAttempts(a, id, 2);
        lab.heal();
        long healed = System.nanoTime();
        home.await("the agent comes home", TRIP, home::allHome);
        long home1 = System.nanoTime();
        home.await("every report comes home", TRIP, home::allReported);
        home.drain(Duration.ofSeconds(30));
        home.assertNothingLostOrDuplicated();
        assertEquals(List.of("a#0:0", "b#0:1", "a#0:2"), home.result(id), "the agent did every stop, b once it was back");
        assertTrue(home.history(id).startsWith("DONE@" + aAddress() + ";DONE@" + bAddress() + ";DONE@" + aAddress()), home.history(id));
        String attempt = failed.get(0);
        assertTrue(attempt.contains(bNs.ip()), "the failed attempt names b's address: " + attempt);
        assertFalse(attempt.contains("127.0.0.1"), "and no other: " + attempt);
        NetFigures.record("next host cut off, less than the patience (21 attempts 1 s apart, 2 s call timeout)",
                String.format("cut %.1f s; %d failed attempts seen before healing; result home %.1f s after healing; reports %d, lost 0, duplicated 0",
                        (healed - cut) / 1e9, failed.size(), (home1 - healed) / 1e9, home.reportsDelivered()));
    }

    @Test
    void nextHostCutOffForLongerThanThePatienceIsSkippedAsUnreachableNamingItsAddress() throws Exception {
        start("nlong", false);
        lab.isolate(bNs);
        long cut = System.nanoTime();
        // Patience: 1 + 2 attempts, 0.5 s apart, each up to the 2 s call timeout: about 7 s.
        String id = home.send("trip 500 2 500 " + aAddress() + "," + bAddress() + "," + aAddress(), 1, TRIP).get(0);
        home.await("the agent comes home without b", TRIP, home::allHome);
        long back = System.nanoTime();
        lab.heal();
        home.await("every report comes home", TRIP, home::allReported);
        home.drain(Duration.ofSeconds(30));
        home.assertNothingLostOrDuplicated();
        assertEquals(List.of("a#0:0", "a#0:2"), home.result(id), "b was skipped, the trip went on");
        String history = home.history(id);
        assertTrue(history.startsWith("DONE@" + aAddress() + ";UNREACHABLE@" + bAddress() + "("), history);
        String why = history.substring(history.indexOf("UNREACHABLE@"), history.indexOf(";DONE@", history.indexOf("UNREACHABLE@")));
        assertTrue(why.contains("connecting to " + bNs.ip() + ":1099 timed out"), "the reason names b's address and what failed: " + why);
        assertFalse(why.contains("127.0.0.1"), "and no other address: " + why);
        assertEquals(2, retryLines(a, id).size(), "a tried 3 times, logging the 2 that were tried again: " + retryLines(a, id));
        NetFigures.record("next host cut off, longer than the patience (3 attempts 0.5 s apart, 2 s call timeout)",
                String.format("skipped as UNREACHABLE; trip home %.1f s after the cut; reports %d, lost 0, duplicated 0", (back - cut) / 1e9,
                        home.reportsDelivered()));
    }

    /** Waits until a host's log has a line matching {@code regex}; returns it. */
    private static String awaitLog(LabProcess host, String what, String regex) {
        Pattern p = Pattern.compile(regex);
        String[] found = new String[1];
        Await.until(what, TRIP, () -> {
            try {
                found[0] = host.log().lines().filter(l -> p.matcher(l).find()).findFirst().orElse(null);
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
            return found[0] != null;
        });
        return found[0];
    }

    @Test
    void homeCutOffWhileReportsAndTheResultAreOwedGetsThemOnceItIsBack() throws Exception {
        start("home", false);
        String id = home.send("trip 1500 5 500 " + aAddress() + "," + bAddress(), 1, TRIP).get(0);
        lab.isolate(homeNs); // the first host has the agent; from now on nothing reaches the home
        long cut = System.nanoTime();
        String homeAddress = homeNs.rmi("home");
        String aOwes = awaitLog(a, "a cannot deliver the agent's report home", "home " + Pattern.quote(homeAddress) + " does not take deliveries");
        String bOwes = awaitLog(b, "b cannot deliver the agent's result home", "home " + Pattern.quote(homeAddress) + " does not take deliveries");
        lab.heal();
        long healed = System.nanoTime();
        home.await("the result comes home", TRIP, home::allHome);
        long back = System.nanoTime();
        home.await("every report comes home", TRIP, home::allReported);
        home.drain(Duration.ofSeconds(30));
        home.assertNothingLostOrDuplicated();
        assertEquals(List.of("a#0:0", "b#0:1"), home.result(id));
        for (String line : List.of(aOwes, bOwes)) {
            assertTrue(line.contains("connecting to " + homeNs.ip() + ":1099") || line.contains(homeNs.ip()), "names the home's address: " + line);
            assertFalse(line.contains("127.0.0.1"), "and no other: " + line);
        }
        awaitLog(b, "b says the home takes deliveries again", "home " + Pattern.quote(homeAddress) + " takes deliveries again");
        NetFigures.record("home cut off while a report (at a) and the result (at b) are owed; 2 s at most between tries",
                String.format("cut %.1f s; result home %.1f s after healing; reports %d, lost 0, duplicated 0", (healed - cut) / 1e9, (back - healed) / 1e9,
                        home.reportsDelivered()));
    }

    @Test
    void aWholeTripOfClonesThroughTwentyPercentLossLosesAndDuplicatesNothing() throws Exception {
        start("loss", false);
        lab.loss(20);
        long t0 = System.nanoTime();
        List<String> ids = home.send("clones 300 10 500 " + aAddress() + "," + bAddress() + " " + aAddress() + "," + bAddress(), 2, TRIP);
        home.await("both clones come home", TRIP, home::allHome);
        home.await("every report comes home", TRIP, home::allReported);
        long t1 = System.nanoTime();
        long dropped = lab.dropped();
        lab.heal();
        home.drain(Duration.ofSeconds(30));
        home.assertNothingLostOrDuplicated();
        assertEquals(List.of("a#0:0", "a#0:1", "b#0:2"), home.result(ids.get(0)), "the clone sent to a toured a and b");
        assertEquals(List.of("b#0:0", "a#0:1", "b#0:2"), home.result(ids.get(1)), "the clone sent to b toured a and b");
        assertTrue(dropped > 0, "the loss rule dropped packets");
        NetFigures.record("20 % of packets lost between all hosts, 2 clones of 3 stops each",
                String.format("trips and reports home in %.1f s; %d packets dropped; reports %d, lost 0, duplicated 0", (t1 - t0) / 1e9, dropped,
                        home.reportsDelivered()));
    }

    @Test
    void aDurableHostKilledWhileItsNextHostIsCutOffResumesTheHopAndNothingIsLost() throws Exception {
        start("kill", true);
        lab.isolate(bNs);
        String id = home.send("trip 500 60 1000 " + aAddress() + "," + bAddress() + "," + aAddress(), 1, TRIP).get(0);
        awaitFailedAttempts(a, id, 1);
        a.kill(); // kill -9 while the agent waits at a to hop to b
        long killed = System.nanoTime();
        a = startA(true);
        awaitLog(a, "a resumes the agent from its store", "resumed");
        lab.heal();
        long healed = System.nanoTime();
        home.await("the agent comes home", TRIP, home::allHome);
        home.await("every report comes home", TRIP, home::allReported);
        long back = System.nanoTime();
        home.drain(Duration.ofSeconds(30));
        home.assertNothingLostOrDuplicated();
        assertEquals(List.of("a#0:0", "b#0:1", "a#0:2"), home.result(id), "the stop at a ran once before the kill, and the trip went on after it");
        NetFigures.record("durable host a killed -9 while its agent waits to hop to b, which is cut off; a restarted during the cut",
                String.format("restarted and cut %.1f s after the kill; result home %.1f s after healing; reports %d, lost 0, duplicated 0, no stop run twice",
                        (healed - killed) / 1e9, (back - healed) / 1e9, home.reportsDelivered()));
    }
}
