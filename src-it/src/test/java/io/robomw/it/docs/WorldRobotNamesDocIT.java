package io.robomw.it.docs;

import io.robomw.it.demo.MwProcess;
import io.robomw.sim.world.WorldLoader;
import org.junit.jupiter.api.Test;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Every {@code --world FILE --world-robot NAME} in README.md and docs/ names a robot the world file has. */
class WorldRobotNamesDocIT {

    private static final Pattern WORLD_ROBOT = Pattern.compile("--world (\\S+\\.yaml)\\s+--world-robot ([A-Za-z0-9._-]+)");

    @Test
    void everyWorldRobotTheDocsNameIsInItsWorld() throws Exception {
        List<Path> pages = new ArrayList<>(List.of(MwProcess.CHECKOUT.resolve("README.md")));
        try (Stream<Path> docs = Files.list(MwProcess.CHECKOUT.resolve("docs"))) {
            docs.filter(p -> p.toString().endsWith(".md")).forEach(pages::add);
        }
        List<String> wrong = new ArrayList<>();
        int checked = 0;
        for (Path page : pages) {
            Matcher m = WORLD_ROBOT.matcher(Files.readString(page));
            while (m.find()) {
                Path world = MwProcess.CHECKOUT.resolve(m.group(1));
                if (!Files.isRegularFile(world)) {
                    continue; // a placeholder (WORLD.yaml) or a file of the reader's
                }
                List<String> names = new WorldLoader().load(world).robots().stream().map(r -> r.name()).toList();
                checked++;
                if (!names.contains(m.group(2))) {
                    wrong.add(MwProcess.CHECKOUT.relativize(page) + ": --world-robot " + m.group(2) + " is not a robot of " + m.group(1) + " " + names);
                }
            }
        }
        assertTrue(checked > 3, "the docs' world robots were found: " + checked);
        assertEquals(List.of(), wrong);
    }
}
