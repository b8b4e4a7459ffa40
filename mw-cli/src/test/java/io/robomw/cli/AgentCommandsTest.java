package io.robomw.cli;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.StartedHosts;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostProbe;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.testkit.Await;
import io.robomw.cli.agents.HelloAgent;
import io.robomw.cli.agents.NoDefaultConstructorAgent;
import io.robomw.cli.agents.RobotAgent;
import io.robomw.cli.agents.TouringAgent;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.jar.JarEntry;
import java.util.jar.JarOutputStream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw dispatch}, {@code mw agents}, {@code mw retract} and {@code mw dispose} run in this JVM
 * against agent hosts on loopback: what an operator sees (summaries, exit codes, one-line errors).
 */
class AgentCommandsTest {

    private static final String DEAD_HOST = "rmi://127.0.0.1:1/gone";

    @TempDir
    Path dir;
    private Path key;
    private Path jar;
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    record Run(int status, String out, String err) {
    }

    @BeforeEach
    void keyAndJar() throws IOException {
        key = Files.writeString(dir.resolve("cluster.key"), "agent commands test");
        jar = dir.resolve("agents.jar");
        try (JarOutputStream out = new JarOutputStream(Files.newOutputStream(jar))) {
            for (Class<?> c : List.of(HelloAgent.class, RobotAgent.class, NoDefaultConstructorAgent.class, TouringAgent.class,
                    io.robomw.cli.agents.HoldingAgent.class)) {
                String entry = c.getName().replace('.', '/') + ".class";
                out.putNextEntry(new JarEntry(entry));
                try (var in = c.getClassLoader().getResourceAsStream(entry)) {
                    in.transferTo(out);
                }
                out.closeEntry();
            }
        }
    }

    private AgentHost host(String name) throws Exception {
        return hosts.start(AgentHost.builder(name).clusterKey(ClusterKey.read(key)).noMessaging().stopGrace(Duration.ZERO));
    }

    private Run mw(String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        var cl = Mw.commandLine();
        cl.setOut(new PrintWriter(out, true));
        cl.setErr(new PrintWriter(err, true));
        int status = cl.execute(args);
        return new Run(status, out.toString(), err.toString());
    }

    private Run dispatch(String... rest) {
        List<String> args = new ArrayList<>(List.of("dispatch", "--key-file", key.toString(), "--jar", jar.toString(), "--timeout", "PT30S", "--wait-hosts", "1s"));
        args.addAll(List.of(rest));
        return mw(args.toArray(String[]::new));
    }

    @Test
    void clonesThatWentAreWaitedForWhenAHostIsDownAndTheSummaryNamesEveryStop() throws Exception {
        AgentHost a = host("a");
        Run run = dispatch("--agent", HelloAgent.class.getName(), "--clone", a.address(), DEAD_HOST);
        assertEquals(0, run.status(), run.toString());
        assertTrue(run.out().contains("[" + DEAD_HOST + "] not sent: "), run.out());
        assertTrue(run.out().contains("[" + a.address() + "] hello from a"), run.out());
        assertTrue(run.out().contains("visited a"), run.out());
        String summary = run.out().substring(run.out().indexOf("summary:"));
        assertTrue(summary.matches("(?s).*\\n  COMPLETED  \\[" + java.util.regex.Pattern.quote(a.address()) + "\\] agent \\S+ ended at "
                + java.util.regex.Pattern.quote(a.address()) + "\\n.*"), summary);
        assertTrue(summary.contains("  NOT-SENT   [" + DEAD_HOST + "]"), summary);
        assertTrue(summary.contains("DONE         " + a.address()), summary);
        assertTrue(summary.matches("(?s).*UNREACHABLE  " + java.util.regex.Pattern.quote(DEAD_HOST) + ": .*Connection refused.*"), summary);
        // The command ends once its home has replied to the calls that brought the results; host a reads
        // that reply a moment later. Had the home closed first, the result would stay owed, retried.
        Await.until("host a owes nothing once the command has ended: " + a.owed(), Duration.ofSeconds(10), () -> a.owed().isEmpty());
    }

    @Test
    void reportsAndResultsArePrefixedWithTheHostTheCloneWasAtNotItsFirstHost() throws Exception {
        AgentHost a = host("a");
        AgentHost b = host("b");
        Run run = dispatch("--agent", TouringAgent.class.getName(), "--arg", b.address(), "--clone", a.address());
        assertEquals(0, run.status(), run.toString());
        assertTrue(run.out().contains("[" + a.address() + "] hello from a"), run.out());
        assertTrue(run.out().contains("[" + b.address() + "] hello from b"), "the report sent from b is prefixed with b: " + run.out());
        assertTrue(run.out().contains("[" + b.address() + "] result:\n  last at b"), "and so is the result: " + run.out());
    }

    @Test
    void aTripWithASkippedStopIsNotSummarisedAsCompleted() throws Exception {
        AgentHost a = host("a");
        Run run = dispatch("--agent", HelloAgent.class.getName(), a.address(), DEAD_HOST, a.address());
        String summary = run.out().substring(run.out().indexOf("summary:"));
        assertTrue(summary.contains("\n  INCOMPLETE [agent "), "the first word says a stop was skipped: " + summary);
        assertTrue(summary.contains("ended at " + a.address() + ", 1 stop unreachable"), summary);
    }

    @Test
    void anAgentRetractedMidStopComesHomeAtOnceAndDispatchShowsItsState() throws Exception {
        AgentHost a = host("a");
        java.util.concurrent.CompletableFuture<Run> dispatching = java.util.concurrent.CompletableFuture.supplyAsync(
                () -> dispatch("--agent", io.robomw.cli.agents.HoldingAgent.class.getName(), a.address()));
        Await.until("the agent works at a", Duration.ofSeconds(30), () -> !a.agents().isEmpty());
        UUID id = a.agents().get(0).id();
        Run retract = mw("retract", "--key-file", key.toString(), id.toString(), a.address());
        assertEquals(0, retract.status(), retract.toString());
        // The agent sleeps a minute; the retract interrupts it, so its state is home long before mw dispatch's 30 s time-out.
        Run run = dispatching.get(60, java.util.concurrent.TimeUnit.SECONDS);
        assertEquals(0, run.status(), run.toString());
        assertTrue(run.out().contains("[" + a.address() + "] RETRACTED: its state came home:\n  " + io.robomw.cli.agents.HoldingAgent.class.getName()
                + "\n    began: at a"), run.out());
        String summary = run.out().substring(run.out().indexOf("summary:"));
        assertTrue(summary.matches("(?s).*\\n  RETRACTED  \\[agent \\S+\\] agent \\S+ came home from " + java.util.regex.Pattern.quote(a.address()) + "\\n.*"),
                summary);
    }

    @Test
    void strictFailsWhenAStopWasSkipped() throws Exception {
        AgentHost a = host("a");
        Run clones = dispatch("--strict", "--agent", HelloAgent.class.getName(), "--clone", a.address(), DEAD_HOST);
        assertEquals(4, clones.status(), clones.toString());
        Run trip = dispatch("--strict", "--agent", HelloAgent.class.getName(), a.address(), DEAD_HOST, a.address());
        assertEquals(4, trip.status(), trip.toString());
        assertTrue(trip.out().contains("UNREACHABLE  " + DEAD_HOST), trip.out());
        assertEquals(0, dispatch("--strict", "--agent", HelloAgent.class.getName(), a.address()).status());
    }

    @Test
    void aStopThatNeedsARobotAtAHostWithoutOneFailsInOneLineAndVerboseShowsTheRemoteTrace() throws Exception {
        AgentHost a = host("a");
        Run run = dispatch("--agent", RobotAgent.class.getName(), a.address());
        assertEquals(1, run.status(), run.toString());
        assertTrue(run.out().contains("FAILED       " + a.address() + ": io.robomw.agents.host.NoRobotException: agent host a (" + a.address()
                + ") has no robot: start it with mw host --robot FILE"), run.out());
        assertFalse(run.out().contains("at io.robomw"), "no stack trace without --verbose: " + run.out());

        Run verbose = dispatch("--verbose", "--agent", RobotAgent.class.getName(), a.address());
        assertTrue(verbose.out().contains("at io.robomw.agents.host.HostContext.robot"), "the remote trace with --verbose: " + verbose.out());
    }

    @Test
    void anAgentClassWithoutAUsableConstructorIsOneClearLine() throws Exception {
        AgentHost a = host("a");
        Run run = dispatch("--agent", NoDefaultConstructorAgent.class.getName(), a.address());
        assertEquals(2, run.status(), run.toString());
        assertEquals("mw dispatch: " + NoDefaultConstructorAgent.class.getName()
                + " has no public no-argument constructor (give --arg TEXT if it has a public constructor taking a String)", run.err().strip());
    }

    @Test
    void aMissingKeyFileIsOneClearLineNamingIt() throws Exception {
        Path missing = dir.resolve("no-such.key");
        Run run = mw("agents", "--key-file", missing.toString(), "rmi://127.0.0.1:1/x");
        assertEquals(2, run.status(), run.toString());
        List<String> lines = run.err().strip().lines().toList();
        assertTrue(lines.get(0).startsWith("mw agents: ") && lines.get(0).contains(missing.toAbsolutePath().toString())
                && lines.get(0).contains("does not exist"), run.err());
        assertFalse(run.err().contains("\tat "), "no stack trace without --verbose: " + run.err());
        assertTrue(mw("agents", "--verbose", "--key-file", missing.toString(), "rmi://127.0.0.1:1/x").err().contains("\tat "), "--verbose shows it");
    }

    /** Sends, as a peer, a test agent whose home is nowhere (a closed port): what it owes stays owed. @return its id */
    private UUID sendWithAGoneHome(AgentHost to, VisitorAgent agent) throws Exception {
        HostProbe probe = new HostProbe(to.address(), ClusterKey.read(key));
        CodeArchive archive = HostProbe.archiveOf(VisitorAgent.class);
        assertEquals("OK ", probe.putArchive(archive.digest(), archive.bytes()));
        byte[] image = HostProbe.image(archive.digest(), HostProbe.state(agent));
        assertEquals("OK ", probe.call(0, image)); // TRANSFER
        return new UUID(java.nio.ByteBuffer.wrap(image, 1, 16).getLong(), java.nio.ByteBuffer.wrap(image, 9, 8).getLong());
    }

    @Test
    void agentsListsSeveralHostsAndWhatTheyOweWithTheirAgeAndDropsIt() throws Exception {
        AgentHost a = host("a");
        AgentHost b = host("b");
        sendWithAGoneHome(a, new VisitorAgent());
        Await.until("a owes the agent's report, visits and result", Duration.ofSeconds(10), () -> a.owed().size() == 3);

        Run list = mw("agents", "--key-file", key.toString(), a.address(), b.address());
        assertEquals(0, list.status(), list.toString());
        assertTrue(list.out().contains("0 agents at " + a.address()) && list.out().contains("0 agents at " + b.address()), list.out());
        assertTrue(list.out().contains("3 deliveries owed by " + a.address()) && list.out().contains("0 deliveries owed by " + b.address()), list.out());
        assertTrue(list.out().matches("(?s).*REPORT +\\d+s +\\d+ +rmi://127\\.0\\.0\\.1:1/probe-home +.*Connection refused.*"), list.out());

        Run drop = mw("agents", "--key-file", key.toString(), "--drop-owed", "rmi://127.0.0.1:1/probe-home", a.address(), b.address());
        assertEquals(0, drop.status(), drop.toString());
        assertTrue(drop.out().contains(a.address() + " dropped 3 owed deliveries") && drop.out().contains(b.address() + " dropped 0"), drop.out());
        assertTrue(a.owed().isEmpty());

        Run partly = mw("agents", "--key-file", key.toString(), a.address(), DEAD_HOST);
        assertEquals(1, partly.status(), partly.toString());
        assertTrue(partly.out().contains("0 agents at " + a.address()), partly.out());
        String down = partly.out().lines().filter(l -> l.startsWith(DEAD_HOST)).findFirst().orElse("");
        assertTrue(down.matches(java.util.regex.Pattern.quote(DEAD_HOST) + "  DOWN  \\(no answer at \\d{4}-\\d\\d-\\d\\dT[0-9:]+Z\\)  cannot connect to 127\\.0\\.0\\.1:1: Connection refused"),
                "one line for the host that is down: which, when, why, in words (no RMI text): " + partly.out());
    }

    @Test
    void agentsTakesHostsOrABrokerNotBoth() {
        Run both = mw("agents", "--cluster", "mqtt://127.0.0.1:1", "rmi://127.0.0.1:1/x");
        assertEquals(2, both.status(), both.toString());
        assertEquals("mw agents: give HOST addresses or --cluster BROKER, not both", both.err().strip());
    }

    @Test
    void disposeFindsTheAgentAndRetractOfAnUnknownAgentSaysNoHostKnowsIt() throws Exception {
        AgentHost a = host("a");
        UUID id = sendWithAGoneHome(a, new VisitorAgent().holdUntilReleased());
        Run dispose = mw("dispose", "--key-file", key.toString(), id.toString(), DEAD_HOST, a.address());
        assertEquals(0, dispose.status(), dispose.toString());
        assertTrue(dispose.out().contains("agent " + id + " ends its trip when its current callback returns: dispose taken at " + a.address()),
                dispose.out());

        UUID nobody = UUID.randomUUID();
        Run retract = mw("retract", "--key-file", key.toString(), nobody.toString(), a.address());
        assertEquals(1, retract.status(), retract.toString());
        assertTrue(retract.err().startsWith("mw retract: no host given knows agent " + nobody), retract.err());
    }
}
