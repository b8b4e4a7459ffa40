package io.robomw.agents.host;

import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The agent host's public API is {@code io.robomw.agents.host} (the facade and its values),
 * {@code host.ops} (asking and watching hosts), {@code host.code} and {@code host.store}; its
 * other packages are its parts, public only so that they can call each other. No other module's
 * main code may use them.
 *
 * <p>Why a test and not a {@code module-info}: the modules that use mw-agents are on the class
 * path, where a module's exports restrict nothing; making them all named modules would need every
 * dependency to be one too, and the test-jars that put tests in the main code's packages split
 * those packages. This test reads the sources, which is what the rule is about.
 */
class InternalPackagesTest {

    private static final Set<String> EXPORTED = Set.of("io.robomw.agents.host", "io.robomw.agents.host.ops",
            "io.robomw.agents.host.code", "io.robomw.agents.host.store");
    private static final Pattern IMPORT = Pattern.compile("\\b(io\\.robomw\\.agents\\.host(?:\\.[a-z]\\w*)*)\\.[A-Z]");

    @Test
    void noOtherModuleImportsTheHostsParts() throws IOException {
        Path root = Path.of("").toAbsolutePath().getParent();
        assertTrue(Files.isDirectory(root.resolve("mw-agents")), "run from mw-agents (the build's working directory): " + root);
        List<String> found = new ArrayList<>();
        int read = 0;
        try (Stream<Path> modules = Files.list(root)) {
            for (Path module : modules.filter(m -> !m.getFileName().toString().equals("mw-agents")).toList()) {
                Path main = module.resolve("src/main/java");
                if (!Files.isDirectory(main)) {
                    continue;
                }
                try (Stream<Path> files = Files.walk(main)) {
                    for (Path f : files.filter(p -> p.toString().endsWith(".java")).toList()) {
                        read++;
                        Matcher m = IMPORT.matcher(Files.readString(f));
                        while (m.find()) {
                            if (!EXPORTED.contains(m.group(1))) {
                                found.add(root.relativize(f) + " uses " + m.group(1));
                            }
                        }
                    }
                }
            }
        }
        assertTrue(read > 100, "read the other modules' main sources (" + read + " files under " + root + ")");
        assertEquals(List.of(), found, "only " + EXPORTED + " are the agent host's API");
    }
}
