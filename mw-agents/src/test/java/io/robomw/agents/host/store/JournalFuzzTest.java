package io.robomw.agents.host.store;

import com.code_intelligence.jazzer.junit.FuzzTest;
import org.junit.jupiter.api.AfterAll;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Comparator;
import java.util.stream.Stream;

/**
 * Fuzz test of the journal a durable host replays when it starts (docs/fuzzing.md): any bytes as
 * the journal file. Opening may refuse the journal only with an {@link IOException} naming the
 * file; what it opens it must be able to open again after rewriting it.
 */
class JournalFuzzTest {

    private static final Path DIR;

    static {
        try {
            DIR = Files.createTempDirectory("journal-fuzz");
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
    void replay(byte[] input) throws IOException {
        Files.write(DIR.resolve("journal"), input);
        try (JournalStore first = JournalStore.open(DIR)) {
            first.recoveredAgents();
        } catch (IOException refused) {
            if (!refused.getMessage().contains(DIR.toString())) {
                throw new AssertionError("a refused journal is not named: " + refused.getMessage(), refused);
            }
            return;
        }
        try (JournalStore again = JournalStore.open(DIR)) {
            again.recoveredEvents();
        }
    }
}
