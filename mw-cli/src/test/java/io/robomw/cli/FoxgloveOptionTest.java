package io.robomw.cli;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import picocli.CommandLine;

import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Issue 37: the Foxglove WebSocket follows the rosbridge's defaults: loopback, or a token from a file or the environment. */
class FoxgloveOptionTest {

    @TempDir
    Path dir;

    @Test
    void aWebSocketBeyondThisMachineWithoutATokenIsRefusedBeforeAnythingListens() {
        StringWriter err = new StringWriter();
        CommandLine cl = Mw.commandLine();
        cl.setOut(new PrintWriter(new StringWriter(), true));
        cl.setErr(new PrintWriter(err, true));
        assertEquals(2, cl.execute("console", "--port", "0", "--foxglove", "0", "--foxglove-bind", "0.0.0.0"));
        assertTrue(err.toString().contains("0.0.0.0") && err.toString().contains("--foxglove-token-file")
                && err.toString().contains("MW_FOXGLOVE_TOKEN"), err.toString());
    }

    @Test
    void theTokenIsTheFilesFirstLineAndAnEmptyFileIsAnError() throws Exception {
        FoxgloveOption o = new FoxgloveOption();
        o.tokenFile = Files.writeString(dir.resolve("token"), "  a-token-of-some-length  \nsecond line\n");
        assertEquals("a-token-of-some-length", o.token());
        o.tokenFile = Files.writeString(dir.resolve("empty"), "\n");
        assertThrows(IllegalArgumentException.class, o::token);
    }
}
