package io.robomw.agents.host;

import io.robomw.testkit.RecordingFailures;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.testkit.Await;
import io.robomw.testkit.Ports;
import io.robomw.api.Agent;
import io.robomw.api.AgentException;
import io.robomw.api.AgentRef;
import io.robomw.api.AgentStatus;
import io.robomw.api.NotHandledException;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import java.io.Serializable;
import java.time.Duration;

import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class AgentHostTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("test cluster");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    private AgentHost host(String name) throws Exception {
        return hosts.start(AgentHost.builder(name).clusterKey(KEY));
    }


    @Test
    void agentVisitsItsStopsInOrderAndBringsItsResultHome() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        VisitorAgent agent = new VisitorAgent();
        agent.itinerary().addStop(a.address()).addStop(b.address()).addStop(a.address());
        AgentRef ref = home.agency().startTrip(agent);
        Serializable result = ref.result().get(60, TimeUnit.SECONDS);
        assertEquals(List.of("a", "b", "a"), result);
        assertEquals(AgentStatus.COMPLETED, ref.status());
        assertEquals(a.address(), ref.location());
    }

    @Test
    void reportsArriveInTheOrderTheAgentSentThem() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().addStop(a.address()).addStop(b.address());
        AgentRef ref = home.agency().startTrip(agent);
        List<Serializable> reports = new CopyOnWriteArrayList<>();
        ref.addReportListener(reports::add);
        assertEquals("a", ref.sendMessage("where", Duration.ofSeconds(5)));
        ref.sendMessage("release", Duration.ofSeconds(5));
        await(() -> "b".equals(safeWhere(ref)));
        ref.sendMessage("release", Duration.ofSeconds(5));
        ref.result().get(60, TimeUnit.SECONDS);
        // The listener was added after the trip began, so "at a" may have come before it; nothing may come out of order.
        assertTrue(reports.equals(List.of("at a", "at b")) || reports.equals(List.of("at b")), "reports in order: " + reports);
    }

    @Test
    void dispatchClonesRunsOneCloneOnEachHostAndReturnsBothResults() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        List<AgentRef> refs = home.agency().dispatchClones(new VisitorAgent(), a.address(), b.address());
        assertEquals(2, refs.size());
        assertNotEquals(refs.get(0).id(), refs.get(1).id());
        assertEquals(List.of("a"), refs.get(0).result().get(60, TimeUnit.SECONDS));
        assertEquals(List.of("b"), refs.get(1).result().get(60, TimeUnit.SECONDS));
    }

    @Test
    void messageTheAgentDoesNotHandleFailsWithNotHandled() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentRef ref = home.agency().sendAgent(a.address(), new VisitorAgent().holdUntilReleased());
        AgentException e = assertThrows(AgentException.class, () -> ref.sendMessage("dance", Duration.ofSeconds(5)));
        assertInstanceOf(NotHandledException.class, e);
        ref.sendMessage("release", Duration.ofSeconds(5));
        ref.result().get(60, TimeUnit.SECONDS);
    }

    @Test
    void retractBringsTheAgentHomeWithItsState() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().addStop(a.address()).addStop(b.address());
        AgentRef ref = home.agency().startTrip(agent);
        List<java.io.Serializable> reports = new java.util.concurrent.CopyOnWriteArrayList<>();
        ref.addReportListener(reports::add);
        // Its work at a has begun: a retract that came earlier (after it arrived, before its work began) would
        // keep the work from beginning, and it would come home without having visited a (HostedAgentTest).
        await(() -> reports.contains("at a"));
        var retracted = ref.retract();
        // The retract takes effect when the stop's work returns; release the agent until it is home.
        await(() -> {
            safeSend(ref, "release");
            return retracted.isDone();
        });
        Agent back = retracted.get(60, TimeUnit.SECONDS);
        assertEquals(List.of("a"), ((VisitorAgent) back).visited());
        assertEquals(AgentStatus.RETRACTED, ref.status());
    }

    @Test
    void disposeEndsTheTripAndFailsTheResult() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().addStop(a.address()).addStop(b.address());
        AgentRef ref = home.agency().startTrip(agent);
        await(() -> "a".equals(safeWhere(ref))); // at a, holding (120 s unless released or interrupted)
        ref.dispose();
        // Not released: the dispose interrupts the agent's work, which ends at once.
        Exception e = assertThrows(Exception.class, () -> ref.result().get(60, TimeUnit.SECONDS));
        assertTrue(e.getCause().getMessage().contains("disposed"), e.getCause().getMessage());
        assertEquals(AgentStatus.DISPOSED, ref.status());
    }

    @Test
    void retractInterruptsAnAgentBlockedInItsWorkAndItsStateComesHomeAtOnce() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        VisitorAgent agent = new VisitorAgent().holdUntilReleased(); // blocks its stop for 120 s unless released or interrupted
        agent.itinerary().addStop(a.address()).addStop(b.address());
        AgentRef ref = home.agency().startTrip(agent);
        List<java.io.Serializable> reports = new java.util.concurrent.CopyOnWriteArrayList<>();
        ref.addReportListener(reports::add);
        await(() -> reports.contains("at a")); // its work at a has begun (not only arrived there)
        Agent back = ref.retract().get(60, TimeUnit.SECONDS); // never released: the retract must not wait for the 120 s hold (60 s is patience for a loaded machine)
        assertEquals(List.of("a"), ((VisitorAgent) back).visited());
        assertEquals(AgentStatus.RETRACTED, ref.status());
    }

    @Test
    void disposeOfAnAgentThatDrivesEndsItsCommandAndStopsTheRobot() throws Exception {
        io.robomw.agents.HeldRobot robot = new io.robomw.agents.HeldRobot(); // its move never ends unless cancelled
        AgentHost home = host("home");
        AgentHost a = hosts.start(AgentHost.builder("a").clusterKey(KEY).robot(robot));
        AgentRef ref = home.agency().sendAgent(a.address(), new io.robomw.agents.host.trip.DrivingAgent());
        await(() -> robot.moves.size() == 1);
        ref.dispose();
        Exception e = assertThrows(Exception.class, () -> ref.result().get(60, TimeUnit.SECONDS));
        assertTrue(e.getCause().getMessage().contains("disposed"), e.getCause().getMessage());
        assertTrue(robot.moves.get(0).isCancelled(), "the agent's command was cancelled (its motors brake)");
        assertTrue(robot.stopEntered.await(10, TimeUnit.SECONDS), "the robot was stopped");
        assertEquals(List.of(io.robomw.api.Itinerary.Outcome.INTERRUPTED), ref.history().stream().map(io.robomw.api.Itinerary.Visit::outcome).toList(),
                "the stop was cut short on purpose: " + ref.history());
    }

    @Test
    void aRetractWhoseAgentIgnoresItsInterruptIsShownPendingAndTakesEffectWhenTheCallbackReturns() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentRef ref = home.agency().sendAgent(a.address(), new io.robomw.agents.host.trip.StubbornAgent());
        List<java.io.Serializable> reports = new java.util.concurrent.CopyOnWriteArrayList<>();
        ref.addReportListener(reports::add);
        // its callback running (not just listed at a: a retract that comes before the callback starts takes effect at once)
        await(() -> reports.contains("waiting"));
        var retracted = ref.retract();
        await(() -> a.agents().stream().anyMatch(i -> i.pending() == AgentInfo.Pending.RETRACT));
        assertEquals("ACTIVE (retract pending)", a.agents().get(0).state());
        assertEquals(List.of(AgentInfo.Pending.RETRACT), AgentHost.list(a.address(), KEY, false).stream().map(AgentInfo::pending).toList(),
                "mw agents sees it too");
        assertTrue(!retracted.isDone(), "the agent has not returned from its callback yet");
        ref.sendOnewayMessage("release");
        Agent back = retracted.get(60, TimeUnit.SECONDS);
        assertInstanceOf(io.robomw.agents.host.trip.StubbornAgent.class, back);
        assertEquals(AgentStatus.RETRACTED, ref.status());
    }

    @Test
    void anAgentHopsToAHostGivenByNameAsMessagesDo() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("lab-b");
        assertEquals(List.of("lab-b"), home.agency().sendAgent(b.address(), new VisitorAgent()).result().get(60, TimeUnit.SECONDS),
                "the home has met lab-b");
        // a has never met lab-b: it asks the agent's home where the host of that name is
        AgentRef ref = home.agency().sendAgent(a.address(), new io.robomw.agents.host.trip.HopByNameAgent("lab-b"));
        assertEquals(List.of("a", "lab-b"), ref.result().get(60, TimeUnit.SECONDS));
        assertEquals(b.address(), ref.location());
    }

    @Test
    void anAgentHoppingToAnUnknownHostNameFailsItsStopNamingTheHostsKnown() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentRef ref = home.agency().sendAgent(a.address(), new io.robomw.agents.host.trip.HopByNameAgent("nowhere"));
        assertThrows(Exception.class, () -> ref.result().get(60, TimeUnit.SECONDS));
        String detail = ref.history().get(0).detail();
        assertTrue(detail.contains("no agent host named 'nowhere' is known at " + a.address()), detail);
    }

    @Test
    void unreachableStopIsSkippedAndRecorded() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        VisitorAgent agent = new VisitorAgent();
        agent.itinerary().addStop(a.address()).addStop("rmi://127.0.0.1:1/nobody").addStop(a.address());
        AgentRef ref = home.agency().startTrip(agent);
        assertEquals(List.of("a", "a"), ref.result().get(60, TimeUnit.SECONDS));
    }

    @Test
    void peerWithTheWrongKeyIsRefusedAndTheHostKeepsServing() throws Exception {
        AgentHost a = host("a");
        AgentHost intruder = AgentHost.builder("intruder").clusterKey(ClusterKey.fromPassphrase("guess")).start();
        hosts.add(intruder);
        AgentException e = assertThrows(AgentException.class, () -> intruder.agency().sendAgent(a.address(), new VisitorAgent()));
        assertTrue(e.getMessage().contains("refused"), e.getMessage());
        assertTrue(a.refused() >= 1);
        AgentHost home = host("home");
        assertEquals(List.of("a"), home.agency().sendAgent(a.address(), new VisitorAgent()).result().get(60, TimeUnit.SECONDS));
    }

    @Test
    void durableHostsCarryALargeAgentThereAndBackAndKeepNothingOnceItIsHome(@org.junit.jupiter.api.io.TempDir java.nio.file.Path dir) throws Exception {
        AgentHost home = AgentHost.builder("home").clusterKey(KEY).store(dir.resolve("home")).start();
        hosts.add(home);
        AgentHost a = AgentHost.builder("a").clusterKey(KEY).store(dir.resolve("a")).start();
        hosts.add(a);
        VisitorAgent agent = new VisitorAgent().payload(300_000);
        agent.itinerary().addStop(a.address()).addStop(home.address()).addStop(a.address()).addStop(home.address());
        assertEquals(List.of("a", "home", "a", "home"), home.agency().startTrip(agent).result().get(60, TimeUnit.SECONDS));
        // The result can be home before host a has read home's acknowledgement of the last hop there
        // (home runs the stop as soon as it has stored the agent): a lists it IN_TRANSIT until then.
        Await.until("host a no longer lists the agent once the hop home is acknowledged", Duration.ofSeconds(10), () -> a.agents().isEmpty());
        a.close();
        AgentHost again = AgentHost.builder("a").clusterKey(KEY).store(dir.resolve("a")).start();
        hosts.add(again);
        assertTrue(again.agents().isEmpty(), "nothing to resume: " + again.agents());
    }

    @Test
    void anAgentThatHopsToTheSameDurableHostIsResumedFromItsNewCopyAfterTheHostStops(@org.junit.jupiter.api.io.TempDir java.nio.file.Path dir)
            throws Exception {
        AgentHost home = host("home");
        AgentHost a = AgentHost.builder("a").clusterKey(KEY).port(Ports.free()).store(dir.resolve("a")).stopGrace(Duration.ZERO).start();
        hosts.add(a);
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().addStop(a.address()).addStop(a.address());
        AgentRef ref = home.agency().startTrip(agent);
        List<Serializable> reports = new CopyOnWriteArrayList<>();
        ref.addReportListener(reports::add); // the first listener gets the reports that came before it
        await(() -> reports.size() == 1);
        ref.sendMessage("release", Duration.ofSeconds(5)); // once: the second stop holds until the host stops
        await(() -> reports.size() == 2);
        // Host a took the hop to itself (the new copy stored) and then recorded the copy that left departed.
        Await.until("host a has recorded the first copy departed", Duration.ofSeconds(10), () -> a.address().equals(a.forwardOf(ref.id())));
        int port = HostAddress.parse(a.address()).port();
        a.close(); // mid-stop at its second stop
        AgentHost again = hosts.restart(AgentHost.builder("a").clusterKey(KEY).port(port).store(dir.resolve("a")));
        ref.result().get(30, TimeUnit.SECONDS); // resumed from the copy that hopped to a again: not lost
        assertEquals(List.of(io.robomw.api.Itinerary.Outcome.DONE, io.robomw.api.Itinerary.Outcome.INTERRUPTED),
                ref.history().stream().map(io.robomw.api.Itinerary.Visit::outcome).toList(), "its second stop cut short, not run twice");
        assertEquals(List.of("at a", "at a"), reports);
    }

    @Test
    void aDurableHomeThatTookARetractedAgentBackStartsAgainWithNothingToResume(@org.junit.jupiter.api.io.TempDir java.nio.file.Path dir)
            throws Exception {
        AgentHost home = AgentHost.builder("home").clusterKey(KEY).port(Ports.free()).store(dir.resolve("home")).start();
        hosts.add(home);
        AgentHost a = host("a");
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().addStop(a.address());
        AgentRef ref = home.agency().startTrip(agent);
        List<java.io.Serializable> reports = new java.util.concurrent.CopyOnWriteArrayList<>();
        ref.addReportListener(reports::add);
        // retracted from its stop at a: a retract sent at once may find it not yet gone, and it comes back having visited nothing
        await(() -> reports.contains("at a"));
        var retracted = ref.retract();
        await(() -> {
            safeSend(ref, "release");
            return retracted.isDone();
        });
        assertEquals(List.of("a"), ((VisitorAgent) retracted.get(60, TimeUnit.SECONDS)).visited());
        int port = HostAddress.parse(home.address()).port();
        home.close();
        AgentHost again = hosts.restart(AgentHost.builder("home").clusterKey(KEY).port(port).store(dir.resolve("home")));
        assertTrue(again.agents().isEmpty(), "the agent is back with its handle, nothing hosted to resume: " + again.agents());
    }

    @Test
    void theTripsVisitsComeHomeWithAFailedStopsRemoteStackTraceAndAnUnreachableStopsReason() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        VisitorAgent agent = new VisitorAgent();
        agent.itinerary().addStop(a.address(), ctx -> ctx.robot()).addStop("rmi://127.0.0.1:1/nobody").addStop(a.address());
        AgentRef ref = home.agency().startTrip(agent);
        assertEquals(List.of("a"), ref.result().get(60, TimeUnit.SECONDS));
        List<io.robomw.api.Itinerary.Visit> visits = ref.history();
        assertEquals(List.of(io.robomw.api.Itinerary.Outcome.FAILED, io.robomw.api.Itinerary.Outcome.UNREACHABLE, io.robomw.api.Itinerary.Outcome.DONE),
                visits.stream().map(io.robomw.api.Itinerary.Visit::outcome).toList(), visits.toString());
        String failed = visits.get(0).detail();
        assertTrue(failed.startsWith("io.robomw.agents.host.NoRobotException: agent host a (" + a.address() + ") has no robot"), failed);
        assertTrue(failed.contains("\tat io.robomw.agents.host.visit.HostContext.robot"), "the remote stack trace: " + failed);
        assertEquals("rmi://127.0.0.1:1/nobody", visits.get(1).host());
        assertTrue(visits.get(1).detail().contains("Connection refused"), visits.get(1).detail());
    }

    @Test
    void anErrorFromAnAgentsCodeThatAThreadSurvivesFailsItsStopAndTheTripGoesOn() throws Exception {
        RecordingFailures failures = new RecordingFailures();
        AgentHost home = host("home");
        AgentHost a = hosts.start(AgentHost.builder("a").clusterKey(KEY).failures(failures));
        VisitorAgent agent = new VisitorAgent();
        agent.itinerary().addStop(a.address(), ctx -> {
            throw new NoClassDefFoundError("org/example/Gone");
        }).addStop(a.address(), ctx -> {
            throw new StackOverflowError("agent code in trouble");
        }).addStop(a.address());
        AgentRef ref = home.agency().startTrip(agent);
        assertEquals(List.of("a"), ref.result().get(60, TimeUnit.SECONDS));
        List<io.robomw.api.Itinerary.Visit> visits = ref.history();
        assertEquals(List.of(io.robomw.api.Itinerary.Outcome.FAILED, io.robomw.api.Itinerary.Outcome.FAILED, io.robomw.api.Itinerary.Outcome.DONE),
                visits.stream().map(io.robomw.api.Itinerary.Visit::outcome).toList(), visits.toString());
        assertTrue(visits.get(0).detail().startsWith("java.lang.NoClassDefFoundError: org/example/Gone"), visits.get(0).detail());
        assertTrue(visits.get(1).detail().startsWith("java.lang.StackOverflowError: agent code in trouble"), visits.get(1).detail());
        List<RecordingFailures.Report> reports = failures.reports();
        assertEquals(List.of(NoClassDefFoundError.class, StackOverflowError.class), reports.stream().map(r -> r.failure().getClass()).toList(),
                "the host's failure policy heard of both: " + reports);
        assertTrue(failures.deaths().isEmpty(), "no runner died: " + reports);
        assertTrue(reports.get(0).owner().startsWith("agent-") && reports.get(0).owner().endsWith("-VisitorAgent@a"),
                "reported under the agent's runner: " + reports.get(0).owner());
    }

    @Test
    void anErrorNoThreadSurvivesEndsThatAgentsTripNamingItAndItsHostAndTheHostServesOn() throws Exception {
        RecordingFailures failures = new RecordingFailures();
        AgentHost home = host("home");
        AgentHost a = hosts.start(AgentHost.builder("a").clusterKey(KEY).failures(failures));
        VisitorAgent doomed = new VisitorAgent();
        doomed.itinerary().addStop(a.address(), ctx -> {
            throw new InternalError("the VM is in trouble");
        }).addStop(a.address());
        AgentRef ref = home.agency().startTrip(doomed);

        Exception e = assertThrows(Exception.class, () -> ref.result().get(60, TimeUnit.SECONDS));
        String why = e.getCause().getMessage();
        assertTrue(why.contains("agent " + ref.id()) && why.contains("died at host a (" + a.address() + ")")
                && why.contains("java.lang.InternalError: the VM is in trouble"), why);
        assertEquals(AgentStatus.FAILED, ref.status());
        Await.until("the runner's death is reported", Duration.ofSeconds(10), () -> !failures.deaths().isEmpty());
        RecordingFailures.Report death = failures.deaths().get(0);
        assertInstanceOf(InternalError.class, death.failure());
        assertTrue(death.owner().endsWith("-VisitorAgent@a"), "reported under the agent's runner: " + death.owner());

        VisitorAgent next = new VisitorAgent();
        next.itinerary().addStop(a.address()).addStop(a.address());
        assertEquals(List.of("a", "a"), home.agency().startTrip(next).result().get(60, TimeUnit.SECONDS), "the host serves on");
        assertEquals(1, failures.deaths().size(), failures.reports().toString());
    }

    @Test
    void clonesThatCouldBeSentTravelWhenOthersCouldNotAndTheirHandlesComeWithTheError() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        io.robomw.api.PartialDispatchException e = assertThrows(io.robomw.api.PartialDispatchException.class,
                () -> home.agency().dispatchClones(new VisitorAgent(), a.address(), "rmi://127.0.0.1:1/nobody"));
        assertEquals(List.of("rmi://127.0.0.1:1/nobody"), List.copyOf(e.unsent().keySet()));
        assertTrue(e.unsent().get("rmi://127.0.0.1:1/nobody").contains("Connection refused"), e.unsent().toString());
        assertEquals(1, e.sent().size());
        assertEquals(List.of("a"), e.sent().get(0).result().get(60, TimeUnit.SECONDS));
    }

    @Test
    void lambdaTasksTravelAndRun() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        VisitorAgent agent = new VisitorAgent();
        agent.itinerary().addStop(a.address(), ctx -> ctx.setResult("task ran at " + ctx.hostName()));
        assertEquals("task ran at a", home.agency().startTrip(agent).result().get(60, TimeUnit.SECONDS));
    }

    private static String safeWhere(AgentRef ref) {
        try {
            return (String) ref.sendMessage("where", Duration.ofSeconds(2));
        } catch (AgentException e) {
            return null;
        }
    }

    private static void safeSend(AgentRef ref, String message) {
        try {
            ref.sendMessage(message, Duration.ofSeconds(2));
        } catch (AgentException e) {
            // it may be between hosts or home already
        }
    }

    static void await(java.util.function.BooleanSupplier condition) {
        Await.until("the condition", Duration.ofSeconds(10), condition);
    }
}
