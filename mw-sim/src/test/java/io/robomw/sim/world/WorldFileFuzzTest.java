package io.robomw.sim.world;

import com.code_intelligence.jazzer.junit.FuzzTest;
import io.robomw.config.description.DescriptionException;
import org.junit.jupiter.api.AfterAll;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Comparator;
import java.util.stream.Stream;

/**
 * Fuzz test of the world file loader (docs/fuzzing.md): any bytes as a world YAML file, beside a
 * valid robot file it may name ({@code robot.yaml}). The only refusal allowed is a
 * {@link DescriptionException} naming the file.
 */
class WorldFileFuzzTest {

    private static final WorldLoader LOADER = new WorldLoader();
    private static final Path DIR;

    static {
        try {
            DIR = Files.createTempDirectory("world-fuzz");
            Files.writeString(DIR.resolve("robot.yaml"), """
                    name: fuzzbot
                    platform: nxt
                    connection: { port: /dev/null }
                    drive:
                      type: differential
                      wheel_diameter: 0.056
                      track_width: 0.112
                      max_speed: 0.30
                      left:  { port: B }
                      right: { port: C }
                    sensors:
                      - { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 } }
                    """);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    @AfterAll
    static void removeDir() throws IOException {
        try (Stream<Path> files = Files.walk(DIR)) {
            for (Path p : files.sorted(Comparator.reverseOrder()).toList()) {
                Files.deleteIfExists(p);
            }
        }
    }

    @FuzzTest
    void worldFile(byte[] input) throws IOException {
        Path world = DIR.resolve("world.yaml");
        Files.write(world, input);
        try {
            LOADER.load(world);
        } catch (DescriptionException refused) {
            if (!refused.getMessage().contains("world.yaml") && !refused.getMessage().contains("robot.yaml")) {
                throw new AssertionError("a refused world file is not named: " + refused.getMessage(), refused);
            }
        }
    }
}
