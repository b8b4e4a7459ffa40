package io.robomw.it.docs;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * docs/first-program.md, run as written: a virtual NXT from {@code mw emulate --write-robot},
 * {@code mw describe} of the file it wrote, README's first program through {@code mw run}, and
 * {@code mw classpath}. And README's first program is the file that runs.
 */
class FirstProgramDocIT {

    @TempDir
    Path scratch;

    @Test
    void thePageRunsAsWritten() throws Exception {
        List<String> commands = DocCommands.commands(MwProcess.CHECKOUT.resolve("docs/first-program.md"));
        assertEquals(5, commands.size(), commands.toString());
        try (DocCommands doc = new DocCommands(scratch)) {
            // As pasted: mw describe starts while mw emulate is still starting, and waits for the file it writes.
            doc.run(commands.get(0), Duration.ZERO);
            String described = doc.run(commands.get(1), Duration.ofSeconds(90));
            assertTrue(described.contains("robot 'nxt-1' on platform 'nxt'"), described);
            assertTrue(Files.readString(scratch.resolve("nxt.yaml")).contains("port: /dev/pts/"), "the robot file points at the brick");

            String ran = doc.run(commands.get(2), Duration.ofSeconds(120));
            Matcher m = Pattern.compile("front range (\\d+) cm; odometry says Pose\\[x=([-0-9.E]+), y=([-0-9.E]+), heading=([-0-9.E]+)(?:, z=[-0-9.E]+)?]").matcher(ran);
            assertTrue(m.find(), ran + "\n" + doc.transcript());
            double cm = Double.parseDouble(m.group(1));
            assertTrue(cm > 10 && cm < 300, "a wall or obstacle in range of the simulated sonar: " + cm);
            Matcher shown = Pattern.compile("front range (\\d+) cm; odometry says").matcher(Files.readString(MwProcess.CHECKOUT.resolve("docs/first-program.md")));
            assertTrue(shown.find(), "the page shows what the program prints");
            assertEquals(cm, Double.parseDouble(shown.group(1)), 10, "the page's range is the one the program prints (within 10 cm): " + ran);
            assertEquals(0.5, Double.parseDouble(m.group(2)), 0.05, "0.5 m forward: " + ran);
            assertEquals(0.3, Double.parseDouble(m.group(3)), 0.05, "then 0.3 m after a left turn: " + ran);
            assertEquals(Math.PI / 2, Double.parseDouble(m.group(4)), 0.1, ran);

            String classpath = doc.run(commands.get(3), Duration.ofSeconds(60));
            assertTrue(classpath.contains("mw-api") && classpath.contains("mw-platform") && classpath.contains("slf4j"), classpath);

            doc.run(commands.get(4), Duration.ofSeconds(30));
        }
    }

    @Test
    void readmesFirstProgramIsTheOneThatRuns() throws Exception {
        String readme = Files.readString(MwProcess.CHECKOUT.resolve("README.md"));
        String program = Files.readString(MwProcess.CHECKOUT.resolve("examples/FirstProgram.java"));
        Matcher block = Pattern.compile("(?s)## A first program\\s+```java\\n(.*?)```").matcher(readme);
        assertTrue(block.find(), "README has its first program");
        for (String line : block.group(1).split("\n")) {
            String code = line.strip();
            if (code.startsWith("try (Robot robot") || code.equals("}")) {
                continue;
            }
            assertTrue(program.contains(code), "examples/FirstProgram.java has README's line: " + code);
        }
        assertTrue(readme.contains("./mw run examples/FirstProgram.java nxt.yaml"), "README runs it");
        assertTrue(program.contains("Robots.open(file)") && program.contains("\"nxt.yaml\""), "it opens the file README names");
    }
}
