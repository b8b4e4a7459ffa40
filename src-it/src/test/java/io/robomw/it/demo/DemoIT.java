package io.robomw.it.demo;

import io.robomw.testkit.Ports;
import io.robomw.testkit.BusyThreads;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import javax.imageio.ImageIO;
import java.awt.image.BufferedImage;
import java.net.InetAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Set;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The product's front door: exactly what {@code ./mw demo} runs (same main class, same class path,
 * its own processes for the hosts), and the same by hand as the quickstart tells it:
 * {@code mw emulate}, {@code mw host}, {@code mw dispatch}.
 */
class DemoIT {

    private static final Path EXAMPLES_JAR = MwProcess.CHECKOUT.resolve("examples/target/examples-0.1.0-SNAPSHOT.jar");

    @TempDir
    Path dir;

    /**
     * The demo with two threads keeping the machine's cores busy all along, as on a loaded host:
     * the NXT behind its emulated Bluetooth link, the fischertechnik interface polled by a link
     * thread that is now and then held up, both within the same tolerances.
     */
    @Test
    @SuppressWarnings("try")
    void demoSendsClonesToTheNxtAndTheFischertechnikRobotAndBringsBothResultsHome() throws Exception {
        Path png = dir.resolve("demo.png");
        try (BusyThreads load = new BusyThreads(2);
             MwProcess demo = MwProcess.startAsOnATerminal("demo", "demo", "--png", png.toString(), "--logs", dir.resolve("logs").toString())) {
            assertEquals(0, demo.waitFor(Duration.ofMinutes(2)), demo.output());
            String out = demo.output();
            // What a terminal shows, standard error included: the demo's lines, not the libraries' INFO lines among its tables.
            assertTrue(out.lines().noneMatch(l -> l.contains(" INFO ")), "no library log line on the terminal:\n" + out);
            assertTrue(Files.readString(dir.resolve("logs").resolve("demo.log")).contains(" INFO "), "they are in the demo's log");
            for (String robot : List.of("nxt", "ft")) {
                String table = out.substring(out.indexOf("== " + robot + " ("));
                assertTrue(table.contains("distance driven       1.600 m"), table);
                Matcher error = Pattern.compile("final pose error\\s+([0-9.]+) m,\\s+([0-9.]+) deg").matcher(table);
                assertTrue(error.find(), table);
                // The fischertechnik interface counts 11 mm impulse-wheel ticks (docs/bricks.md): a tick lost in a turn would be ~11 degrees.
                assertTrue(Double.parseDouble(error.group(1)) < 0.10, robot + " ends within 10 cm of its start: " + error.group(0));
                assertTrue(Double.parseDouble(error.group(2)) < 20, robot + " ends within 20 degrees of its start heading: " + error.group(0));
                Matcher samples = Pattern.compile("samples\\s+(\\d+)").matcher(table);
                assertTrue(samples.find());
                assertEquals(16, Integer.parseInt(samples.group(1)), robot + " brought 16 range samples home");
            }
            assertTrue(out.contains("stopped both hosts"), out);
        }
        BufferedImage image = ImageIO.read(png.toFile());
        Set<Integer> colours = new HashSet<>();
        for (int y = 0; y < image.getHeight(); y += 2) {
            for (int x = 0; x < image.getWidth(); x += 2) {
                colours.add(image.getRGB(x, y));
            }
        }
        assertTrue(colours.size() > 20, "the picture is not blank: " + colours.size() + " colours");
    }

    @Test
    void demoWithTheAiboSendsAThirdCloneToTheDogThroughItsUrbiEmulator() throws Exception {
        try (MwProcess demo = MwProcess.start("demo-aibo", "demo", "--robots", "nxt,ft,aibo", "--png", dir.resolve("demo3.png").toString(),
                "--logs", dir.resolve("logs3").toString())) {
            assertEquals(0, demo.waitFor(Duration.ofMinutes(3)), demo.output());
            String out = demo.output();
            assertTrue(out.contains("virtual Sony Aibo (URBI server) for aibo on tcp 127.0.0.1:"), out);
            for (String robot : List.of("nxt", "ft", "aibo")) {
                String table = out.substring(out.indexOf("== " + robot + " ("));
                assertTrue(table.contains("distance driven       1.600 m"), table);
                Matcher samples = Pattern.compile("samples\\s+(\\d+)").matcher(table);
                assertTrue(samples.find());
                assertEquals(16, Integer.parseInt(samples.group(1)), robot + " brought 16 range samples home");
            }
            // The dog's gait loses 2 % of each motion and varies 3 % step by step (aibo.yaml): a 0.4 m
            // square in 0.1 m steps ends some 4 cm from its start, 7° off its heading; 10 cm and 20° bound it.
            String dog = out.substring(out.indexOf("== aibo ("));
            Matcher error = Pattern.compile("final pose error\\s+([0-9.]+) m,\\s+([0-9.]+) deg").matcher(dog);
            assertTrue(error.find(), dog);
            assertTrue(Double.parseDouble(error.group(1)) < 0.10, "the dog ends within 10 cm of its start: " + error.group(0));
            assertTrue(Double.parseDouble(error.group(2)) < 20, "and within 20 degrees of its heading: " + error.group(0));
            assertTrue(dog.contains("(the robot's own dead reckoning from its commanded gait)"), "a dog has no encoders: " + dog);
            assertTrue(out.contains("stopped all 3 hosts"), out);
        }
    }

    @Test
    void emulateAiboServesUrbiOnTheTcpPortItPrints() throws Exception {
        try (MwProcess dog = MwProcess.start("emulate-aibo", "emulate", "aibo", "--world", "examples/worlds/arena.yaml", "--robot", "aibo", "--tcp", "0")) {
            String where = dog.await("tcp://", Duration.ofSeconds(60)).strip();
            int port = Integer.parseInt(where.substring(where.lastIndexOf(':') + 1));
            try (java.net.Socket s = new java.net.Socket(InetAddress.getLoopbackAddress(), port)) {
                s.getOutputStream().write("p1: ping;\n".getBytes(java.nio.charset.StandardCharsets.US_ASCII));
                java.io.BufferedReader in = new java.io.BufferedReader(new java.io.InputStreamReader(s.getInputStream(), java.nio.charset.StandardCharsets.US_ASCII));
                String line;
                do {
                    line = in.readLine();
                } while (line != null && !line.contains(":p1]"));
                assertTrue(line != null && line.matches("\\[\\d{8}:p1] \\*\\*\\* pong time=.*"), "the answer to ping: " + line);
            }
        }
    }

    @Test
    void theSameAgentJarDispatchedByHandToHostsStartedByHandGivesTheSameResults() throws Exception {
        Path key = Files.writeString(dir.resolve("cluster.key"), "quickstart passphrase\n");
        List<MwProcess> running = new ArrayList<>();
        try {
            MwProcess nxtBrick = MwProcess.start("quickstart-emulate-nxt", "emulate", "nxt", "--world", "examples/worlds/arena.yaml", "--robot", "nxt");
            running.add(nxtBrick);
            MwProcess ftBrick = MwProcess.start("quickstart-emulate-ft", "emulate", "ft-intelligent", "--world", "examples/worlds/arena.yaml", "--robot", "ft");
            running.add(ftBrick);
            String nxtDevice = nxtBrick.await("/dev/", Duration.ofSeconds(60)).strip();
            String ftDevice = ftBrick.await("/dev/", Duration.ofSeconds(60)).strip();
            int nxtPort = Ports.free();
            int ftPort = Ports.free();
            MwProcess nxtHost = MwProcess.start("quickstart-host-nxt", "host", "--robot", "examples/robots/nxt-two-wheeled.yaml", "--connection", "port=" + nxtDevice,
                    "--port", String.valueOf(nxtPort), "--name", "nxt", "--key-file", key.toString());
            running.add(nxtHost);
            MwProcess ftHost = MwProcess.start("quickstart-host-ft", "host", "--robot", "examples/robots/ft-intelligent.yaml", "--connection", "port=" + ftDevice,
                    "--port", String.valueOf(ftPort), "--name", "ft", "--key-file", key.toString());
            running.add(ftHost);
            nxtHost.await("ready at", Duration.ofSeconds(60));
            ftHost.await("ready at", Duration.ofSeconds(60));
            MwProcess dispatch = MwProcess.start("quickstart-dispatch", "dispatch", "--key-file", key.toString(), "--jar", EXAMPLES_JAR.toString(),
                    "--agent", "io.robomw.examples.agents.SquareSurveyAgent", "--clone",
                    "rmi://127.0.0.1:" + nxtPort + "/nxt", "rmi://127.0.0.1:" + ftPort + "/ft");
            running.add(dispatch);
            assertEquals(0, dispatch.waitFor(Duration.ofMinutes(2)), dispatch.output());
            String out = dispatch.output();
            for (String robot : List.of("nxt", "ft")) {
                // "[HOST ID] result:" names the host the clone was at when its trip ended
                String block = out.substring(out.indexOf("[rmi://127.0.0.1:" + (robot.equals("nxt") ? nxtPort : ftPort) + "/" + robot + " "));
                block = block.substring(block.indexOf("] result:"));
                assertTrue(block.contains("distanceDriven: 1.6000"), block);
                Matcher closure = Pattern.compile("odometryClosure: ([0-9.]+)").matcher(block);
                assertTrue(closure.find(), block);
                assertTrue(Double.parseDouble(closure.group(1)) < 0.05, robot + ": " + closure.group(0));
                assertTrue(block.contains("(16 in all)"), robot + " brought 16 samples: " + block);
            }
        } finally {
            for (MwProcess p : running) {
                p.close();
            }
        }
    }
}
