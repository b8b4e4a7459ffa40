package io.robomw.sim.render;

import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.awt.GraphicsEnvironment;
import java.awt.HeadlessException;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

/**
 * The window itself needs a display and is tried by hand (docs/simulation.md); its drawing and
 * controls are tested headless in {@link PngRendererTest}, {@link ViewTransformTest} and
 * {@link RealTimeControlTest}.
 */
class SimViewerTest {

    @TempDir
    Path dir;

    @Test
    void shouldRefuseToOpenWithoutDisplayAndLeaveSimulationStopped() throws Exception {
        assumeTrue(GraphicsEnvironment.isHeadless(), "this machine has a display");
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            HeadlessException e = assertThrows(HeadlessException.class, () -> SimViewer.open(sim, RenderOptions.DEFAULT, 1));
            assertTrue(e.getMessage().contains("no display"), e.getMessage());
            sim.runFor(Duration.ofMillis(10));
        }
    }
}
