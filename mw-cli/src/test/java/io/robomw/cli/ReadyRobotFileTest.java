package io.robomw.cli;

import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The robot file {@code mw emulate --write-robot} writes: the emulator's connection, everything else kept. */
class ReadyRobotFileTest {

    @TempDir
    Path dir;

    @Test
    void aSerialRobotGetsThePseudoTerminalAndKeepsTheRest() throws IOException {
        Path source = Path.of("../examples/robots/nxt-two-wheeled.yaml");
        Path ready = dir.resolve("sub/nxt.yaml");
        ReadyRobotFile.write(source, ready, Map.of("port", "/dev/pts/42"), "mw emulate nxt");
        RobotDescription original = new RobotDescriptionLoader().load(source);
        RobotDescription d = new RobotDescriptionLoader().load(ready);
        assertEquals("/dev/pts/42", d.connection().text("port").orElseThrow());
        assertEquals("115200", d.connection().text("baud").orElseThrow());
        assertEquals(original.sensors(), d.sensors());
        assertEquals(original.drive(), d.drive());
        String text = Files.readString(ready);
        assertTrue(text.startsWith("# Written by mw emulate nxt from " + source), text);
        assertTrue(text.contains("# m/s at the wheel rim"), "the file's comments stay");
        assertFalse(text.contains("rfcomm"), text);
    }

    @Test
    void aTcpRobotGetsHostAndPortAndAFlowStyleConnectionIsRewritten() throws IOException {
        Path source = dir.resolve("txt.yaml");
        String txt = Files.readString(Path.of("../examples/robots/ft-txt.yaml"));
        Files.writeString(source, txt.replaceFirst("connection:\\n( +.*\\n)+", "connection: { host: 192.168.7.2, port: 65000, reply_timeout_ms: 700 }\n"));
        assertTrue(Files.readString(source).contains("connection: { host"), Files.readString(source));
        Path ready = dir.resolve("ready.yaml");
        Map<String, String> tcp = new LinkedHashMap<>();
        tcp.put("host", "127.0.0.1");
        tcp.put("port", "40123");
        ReadyRobotFile.write(source, ready, tcp, "mw emulate ft-txt");
        RobotDescription d = new RobotDescriptionLoader().load(ready);
        assertEquals("127.0.0.1", d.connection().text("host").orElseThrow());
        assertEquals(40123, d.connection().integer("port", 0));
        assertEquals(700, d.connection().integer("reply_timeout_ms", 0));
    }
}
