package io.robomw.agents.messaging.mqtt;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class BrokerCredentialsTest {

    @TempDir
    Path dir;

    @Test
    void aFileGivesUserAndPassword() throws IOException {
        Path f = Files.writeString(dir.resolve("mqtt.properties"), "username=robot\npassword=s3cret\n");
        BrokerCredentials c = BrokerCredentials.load(f, Map.of(BrokerCredentials.USERNAME_ENV, "ignored"));
        assertEquals("robot", c.username());
        assertArrayEquals("s3cret".getBytes(StandardCharsets.UTF_8), c.password());
        assertTrue(!c.toString().contains("s3cret"));
    }

    @Test
    void theEnvironmentGivesThemWithoutAFile() throws IOException {
        Path pw = Files.writeString(dir.resolve("pw"), "from-file\n");
        BrokerCredentials c = BrokerCredentials.load(null, Map.of(BrokerCredentials.USERNAME_ENV, "robot", BrokerCredentials.PASSWORD_FILE_ENV, pw.toString()));
        assertArrayEquals("from-file".getBytes(StandardCharsets.UTF_8), c.password());
        c = BrokerCredentials.load(null, Map.of(BrokerCredentials.USERNAME_ENV, "robot", BrokerCredentials.PASSWORD_ENV, "direct"));
        assertArrayEquals("direct".getBytes(StandardCharsets.UTF_8), c.password());
    }

    @Test
    void nothingGivenIsAnonymous() throws IOException {
        assertSame(BrokerCredentials.NONE, BrokerCredentials.load(null, Map.of()));
        assertNull(BrokerCredentials.NONE.username());
    }

    @Test
    void aFileWithoutUserOrUnreadableIsAnErrorNamingIt() throws IOException {
        Path f = Files.writeString(dir.resolve("bad"), "password=x\n");
        IOException e = assertThrows(IOException.class, () -> BrokerCredentials.load(f, Map.of()));
        assertTrue(e.getMessage().contains(f.toString()) && e.getMessage().contains("username"), e.getMessage());
        Path missing = dir.resolve("missing");
        e = assertThrows(IOException.class, () -> BrokerCredentials.load(missing, Map.of()));
        assertTrue(e.getMessage().contains(missing.toString()), e.getMessage());
    }
}
