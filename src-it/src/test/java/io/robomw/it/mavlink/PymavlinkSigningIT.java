package io.robomw.it.mavlink;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Message signing with an independent implementation: {@code mw emulate mavlink --signing-key-file}
 * against pymavlink 2.4.50's own signing (pymavlink_signing.py): a key made as MAVProxy's
 * {@code signing setup} makes it (SHA-256 of the passphrase) is accepted both ways; a wrong key, or
 * no signature, gets no answer.
 */
class PymavlinkSigningIT {

    private static final Duration WAIT = Duration.ofSeconds(60);

    @Test
    void signedFramesAreAcceptedAndAWrongKeyOrNoneIsRefused(@TempDir Path dir) throws Exception {
        Path key = Files.writeString(dir.resolve("harbour.key"), "harbour master\n");
        int port = VehiclePython.freeUdpPort();
        try (MwProcess vehicle = MwProcess.start("signing-boat", "emulate", "mavlink", "--world", "examples/worlds/harbour.yaml", "--robot", "boat",
                "--udp", String.valueOf(port), "--signing-key-file", key.toString())) {
            vehicle.await("udp://127.0.0.1:" + port, WAIT);
            for (String mode : List.of("right", "wrong", "unsigned")) {
                try (VehiclePython client = VehiclePython.start("pymavlink-signing-" + mode, "pymavlink_signing.py", "udpout:127.0.0.1:" + port,
                        key.toString(), mode)) {
                    List<String> ok = client.expectDone(WAIT);
                    String expected = mode.equals("right") ? "OK arm ACCEPTED, addressed to 255/190" : "OK refused";
                    assertTrue(ok.stream().anyMatch(l -> l.startsWith(expected)), mode + ": " + ok);
                }
            }
        }
    }
}
