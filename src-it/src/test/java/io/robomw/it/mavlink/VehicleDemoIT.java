package io.robomw.it.mavlink;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import javax.imageio.ImageIO;
import java.awt.image.BufferedImage;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The paper's scenario on land, in the air and at sea: {@code mw demo --robots nxt,copter,boat}
 * sends clones of one agent (the unchanged SquareSurveyAgent: it takes off when its robot flies) to
 * the NXT behind its virtual brick and to a copter and a boat behind emulated ArduPilots over UDP,
 * each through its real driver in its own agent host; all three bring their squares home.
 */
class VehicleDemoIT {

    @TempDir
    Path dir;

    @Test
    void clonesDriveTheirSquareOnLandInTheAirAndOnTheWater() throws Exception {
        Path png = dir.resolve("harbour.png");
        try (MwProcess demo = MwProcess.start("demo-vehicles", "demo", "--robots", "nxt,copter,boat", "--png", png.toString(),
                "--logs", dir.resolve("logs").toString())) {
            assertEquals(0, demo.waitFor(Duration.ofMinutes(4)), demo.output());
            String out = demo.output();
            assertTrue(out.contains("world harbour"), out);
            assertTrue(out.contains("virtual MAVLink vehicle"), out);
            assertTrue(out.contains("[copter] copter: took off to 2.0 m"), out);
            for (String robot : List.of("nxt", "copter", "boat")) {
                String table = out.substring(out.indexOf("== " + robot + " ("));
                assertTrue(table.contains("distance driven       8.000 m"), table);
                Matcher samples = Pattern.compile("samples\\s+(\\d+)").matcher(table);
                assertTrue(samples.find());
                assertEquals(16, Integer.parseInt(samples.group(1)), robot + " brought 16 range samples home");
            }
            String copter = out.substring(out.indexOf("== copter ("));
            Matcher closure = Pattern.compile("odometry closure\\s+([0-9.]+) m").matcher(copter);
            assertTrue(closure.find());
            assertTrue(Double.parseDouble(closure.group(1)) < 0.5, "the copter's square closes within 0.5 m: " + closure.group(0));
        }
        BufferedImage image = ImageIO.read(png.toFile());
        assertEquals(1000, image.getWidth());
    }
}
