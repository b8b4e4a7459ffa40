package io.robomw.sim;

import io.robomw.testkit.RecordingFailures;

import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.PlatformServices;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * What the thread that steps a world does with what it catches, through the failure policy the
 * simulation was given: a survivable failure fails what it concerns and the clock goes on; any
 * other halts the world, and every program waiting for a robot is released with an error naming it.
 */
class SimulationFailuresTest {

    private static final Duration RELEASED_WITHIN = Duration.ofSeconds(10);

    @TempDir
    Path dir;

    private final RecordingFailures failures = new RecordingFailures();

    /** Two robots, r1 at (1, 1) and r2 at (1, 2), facing +x, in a world named 'failing'. */
    private Simulation world() throws IOException {
        Files.writeString(dir.resolve("scout.yaml"), """
                name: scout
                platform: sim
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.30
                  left:  { port: B }
                  right: { port: C }
                body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
                """);
        Files.writeString(dir.resolve("world.yaml"), """
                name: failing
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: scout.yaml, name: r1, x: 1, y: 1, heading: 0 }
                  - { robot: scout.yaml, name: r2, x: 1, y: 2, heading: 0 }
                """);
        return Simulation.load(dir.resolve("world.yaml"), Set.of(), PlatformServices.none().with(FailurePolicy.class, failures));
    }

    /** @return a program on a thread of its own, calling the robot, and how it ended */
    private static CompletableFuture<Void> program(String name, Runnable calls) {
        CompletableFuture<Void> ended = new CompletableFuture<>();
        Thread t = new Thread(() -> {
            try {
                calls.run();
                ended.complete(null);
            } catch (Throwable e) {
                ended.completeExceptionally(e);
            }
        }, name);
        t.setDaemon(true);
        t.start();
        return ended;
    }

    private static boolean threadAlive(String name) {
        return Thread.getAllStackTraces().keySet().stream().anyMatch(t -> t.getName().equals(name) && t.isAlive());
    }

    /** A step listener that throws once, when the world's time has passed a mark. */
    private static Runnable throwingOnceAfter(Simulation sim, double seconds, Throwable what) {
        AtomicBoolean thrown = new AtomicBoolean();
        return () -> {
            if (sim.world().time() >= seconds && thrown.compareAndSet(false, true)) {
                if (what instanceof Error e) {
                    throw e;
                }
                throw (RuntimeException) what;
            }
        };
    }

    @Test
    void shouldReleaseTheWaitingProgramWithAnErrorNamingWhatKilledTheRealTimeThreadAndStopTheRobots() throws Exception {
        try (Simulation sim = world()) {
            Robot r1 = sim.robot("r1");
            sim.startRealTime(4);
            CompletableFuture<Void> program = program("program-1", () -> r1.move(2.0, 0.05)); // 40 s of motion: its own deadline is far
            SimRobot body = sim.world().robot("r1");
            Await.until("r1 drove 2 cm", Duration.ofSeconds(20), () -> body.pose().x() > 1.02);
            OutOfMemoryError injected = new OutOfMemoryError("injected by the test");
            sim.addStepListener(throwingOnceAfter(sim, 0, injected));

            ExecutionException released = assertThrows(ExecutionException.class, () -> program.get(RELEASED_WITHIN.toSeconds(), TimeUnit.SECONDS));

            assertInstanceOf(RobotException.class, released.getCause());
            String message = released.getCause().getMessage();
            assertTrue(message.contains("OutOfMemoryError: injected by the test") && message.contains("simulation 'failing'")
                    && message.contains("sim-failing"), message);
            // The programs are released first; the policy hears of the death as the thread ends.
            Await.until("the death reported", RELEASED_WITHIN, () -> failures.count() > 0);
            assertEquals(java.util.List.of(new RecordingFailures.Report("sim-failing", injected, true)), failures.reports());
            Await.until("the real-time thread ended", Duration.ofSeconds(10), () -> !threadAlive("sim-failing"));
            for (String name : new String[]{"r1", "r2"}) {
                SimRobot r = sim.world().robot(name);
                assertEquals(0.0, Math.hypot(sim.world().physics().vx(r.body()), sim.world().physics().vy(r.body())), 1e-12,
                        name + "'s motors were stopped");
            }
            assertTrue(sim.failure().isPresent());
            long asked = System.nanoTime();
            RobotException later = assertThrows(RobotException.class, () -> sim.robot("r2").move(0.1, 0.1));
            assertTrue(later.getMessage().contains("OutOfMemoryError: injected by the test"), later.getMessage());
            assertTrue(System.nanoTime() - asked < Duration.ofSeconds(5).toNanos(), "a later call fails at once");
            RobotException again = assertThrows(RobotException.class, () -> sim.startRealTime(1));
            assertTrue(again.getMessage().contains("OutOfMemoryError: injected by the test"), again.getMessage());
        }
    }

    @Test
    void shouldCountASurvivableErrorOfAStepListenerAndKeepTheClockGoing() throws Exception {
        try (Simulation sim = world()) {
            Robot r1 = sim.robot("r1");
            AssertionError injected = new AssertionError("a listener's bug");
            sim.addStepListener(throwingOnceAfter(sim, 0.2, injected));
            sim.startRealTime(4);

            CompletableFuture<Void> program = program("program-1", () -> r1.move(0.3, 0.2));

            program.get(60, TimeUnit.SECONDS);
            assertEquals(1.3, sim.world().robot("r1").pose().x(), 0.01, "the move ended where it should: time went on");
            assertEquals(1, failures.count(), failures.reports().toString());
            RecordingFailures.Report report = failures.reports().get(0);
            assertSame(injected, report.failure());
            assertFalse(report.died());
            assertTrue(report.owner().startsWith("sim-failing: step listener"), report.owner());
            assertTrue(threadAlive("sim-failing"));
            assertTrue(sim.failure().isEmpty());
        }
    }

    @Test
    void shouldEndOnlyTheCommandsOfTheRobotWhoseStepFailedAndDriveTheOthersOn() throws Exception {
        try (Simulation sim = world()) {
            Robot r1 = sim.robot("r1");
            Robot r2 = sim.robot("r2");
            int index = sim.world().robot("r1").index();
            StackOverflowError injected = new StackOverflowError("r1's controller recursed");
            AtomicBoolean thrown = new AtomicBoolean();
            sim.world().addRobotController(1, i -> {
                if (i == index && sim.world().time() >= 0.5 && thrown.compareAndSet(false, true)) {
                    throw injected;
                }
            });
            AtomicReference<Throwable> r1Failure = new AtomicReference<>();

            sim.run(Duration.ofSeconds(60), () -> {
                try {
                    r1.move(1.0, 0.2);
                } catch (RobotLinkException e) {
                    r1Failure.set(e);
                }
            }, () -> r2.move(0.5, 0.2));

            assertInstanceOf(RobotLinkException.class, r1Failure.get(), "r1's move ended with its failure");
            assertTrue(r1Failure.get().getMessage().contains("robot 'r1'") && r1Failure.get().getMessage().contains("r1's controller recursed"),
                    r1Failure.get().getMessage());
            assertTrue(sim.world().robot("r1").pose().x() < 1.2, "r1 stopped soon after: " + sim.world().robot("r1").pose());
            assertEquals(1.5, sim.world().robot("r2").pose().x(), 0.01, "r2 drove on to the end of its move");
            assertEquals(1, failures.count(), failures.reports().toString());
            assertEquals("sim-failing: robot 'r1'", failures.reports().get(0).owner());
            assertFalse(failures.reports().get(0).died());

            sim.run(Duration.ofSeconds(60), () -> r1.move(0.2, 0.2));
            assertTrue(sim.failure().isEmpty(), "and r1 takes commands again");
        }
    }

    @Test
    void shouldReleaseTheProgramsOfAFastRunWhoseStepDiesAndTellItsCaller() throws Exception {
        try (Simulation sim = world()) {
            Robot r1 = sim.robot("r1");
            InternalError injected = new InternalError("the VM broke, says the test");
            sim.addStepListener(throwingOnceAfter(sim, 0.5, injected));
            AtomicReference<Throwable> programFailure = new AtomicReference<>();

            InternalError thrown = assertThrows(InternalError.class, () -> sim.run(Duration.ofSeconds(60), () -> {
                try {
                    r1.move(1.0, 0.2);
                } catch (RuntimeException e) {
                    programFailure.set(e);
                }
            }));

            assertSame(injected, thrown);
            Await.until("the program was released", RELEASED_WITHIN, () -> programFailure.get() != null);
            assertInstanceOf(RobotException.class, programFailure.get());
            assertTrue(programFailure.get().getMessage().contains("InternalError: the VM broke, says the test"), programFailure.get().getMessage());
            assertEquals(1, failures.deaths().size(), failures.reports().toString());
            RobotException refused = assertThrows(RobotException.class, () -> sim.run(Duration.ofSeconds(1), () -> { }));
            assertTrue(refused.getMessage().startsWith("cannot run programs: simulation 'failing'"), refused.getMessage());
        }
    }
}
