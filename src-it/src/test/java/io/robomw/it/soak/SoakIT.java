package io.robomw.it.soak;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;

/**
 * The short soak and kill runs of {@code mvn verify} (the long ones: {@link SoakRun}, in the soak
 * profile, docs/reliability.md): agents going round four host JVMs, and agents in flight while
 * the durable host is killed with -9 and restarted. No agent lost, no stop run twice, no report
 * lost or duplicated at the home, and no host holding more threads, files or heap after than
 * before beyond the bounds.
 */
class SoakIT {

    @TempDir
    Path dir;

    @Test
    void agentsGoingRoundFourHostsForSecondsLoseNothingAndLeaveNothingBehind() throws Exception {
        try (Soak soak = new Soak(new Soak.Plan("hop", 4, 100, Duration.ofSeconds(8), 2, null, Duration.ofSeconds(60)), dir)) {
            soak.start();
            SoakChecks.check(soak.run());
        }
    }

    @Test
    void agentsInFlightWhileTheDurableHostIsKilledLoseNothingAndNoStopRunsTwice() throws Exception {
        try (Soak soak = new Soak(new Soak.Plan("kill", 4, 20, Duration.ofSeconds(12), 30, Duration.ofSeconds(5), Duration.ofSeconds(90)), dir)) {
            soak.start();
            Soak.Figures f = soak.run();
            SoakChecks.check(f);
            org.junit.jupiter.api.Assertions.assertTrue(f.kills() >= 2, "the durable host was killed: " + Soak.describe(f));
        }
    }
}
