package io.robomw.it.security;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;

/** What the security tests share: a cluster key file, free loopback ports, an agent host's port from its address. */
final class Attacker {

    /** The passphrase of the cluster the tests' hosts belong to (the attacker does not have it, the real peers do). */
    static final String PASSPHRASE = "security cluster";

    private Attacker() {
    }

    /** @return a key file (mode 600) holding {@link #PASSPHRASE} */
    static Path keyFile(Path dir) throws IOException {
        Path f = dir.resolve("cluster.key");
        Files.writeString(f, PASSPHRASE + "\n", StandardCharsets.UTF_8);
        Files.setPosixFilePermissions(f, PosixFilePermissions.fromString("rw-------"));
        return f;
    }

    /** @return the port of an agent host's address, rmi://HOST:PORT/NAME */
    static int port(String hostAddress) {
        return Integer.parseInt(hostAddress.replaceAll("^rmi://[^:]+:(\\d+)/.*$", "$1"));
    }
}
