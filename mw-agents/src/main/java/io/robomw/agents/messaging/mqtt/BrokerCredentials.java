package io.robomw.agents.messaging.mqtt;

import java.io.IOException;
import java.io.Reader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermission;
import java.util.Map;
import java.util.Properties;
import java.util.Set;

/**
 * The user name and password a node gives the broker, from a file or the environment, never from
 * a command line or an address (both show in process lists and logs). In order:
 * <ol>
 * <li>the file named by the address option {@code credentials=FILE}: lines {@code username=...} and
 *     {@code password=...} (Java properties, UTF-8);</li>
 * <li>the environment: {@code MW_MQTT_USERNAME}, with {@code MW_MQTT_PASSWORD} or
 *     {@code MW_MQTT_PASSWORD_FILE} (a file holding only the password);</li>
 * <li>for a broker on this machine (a loopback address), the file {@code mw broker} generated,
 *     {@link #defaultFile()} ({@code ~/.robomw/broker.credentials}), if it exists: only the user who
 *     started that broker can read it, and it is never sent to a broker elsewhere;</li>
 * <li>none: the broker is asked to let the client in anonymously.</li>
 * </ol>
 * A file that others may read is used, with a warning in the log.
 *
 * @param username the user name, or {@code null} for none
 * @param password the password, or {@code null} for none
 */
public record BrokerCredentials(String username, byte[] password) {

    /** Environment variable of the user name. */
    public static final String USERNAME_ENV = "MW_MQTT_USERNAME";
    /** Environment variable of the password. */
    public static final String PASSWORD_ENV = "MW_MQTT_PASSWORD";
    /** Environment variable naming a file that holds the password. */
    public static final String PASSWORD_FILE_ENV = "MW_MQTT_PASSWORD_FILE";

    /** No credentials. */
    public static final BrokerCredentials NONE = new BrokerCredentials(null, null);

    /** @return where {@code mw broker} keeps the credentials it generated: {@code ~/.robomw/broker.credentials} */
    public static Path defaultFile() {
        return Path.of(System.getProperty("user.home"), ".robomw", "broker.credentials");
    }

    /**
     * {@link #load(Path, Map)}, and for a broker on this machine with neither, the credentials
     * {@code mw broker} generated ({@link #defaultFile()}) if that file exists.
     *
     * @param file       the credentials file of the address, or {@code null}
     * @param env        the environment
     * @param brokerHost the broker's host, as the address names it
     * @return the credentials
     * @throws IOException naming the file that cannot be read or lacks a user name
     */
    public static BrokerCredentials load(Path file, Map<String, String> env, String brokerHost) throws IOException {
        BrokerCredentials given = load(file, env);
        if (given != NONE || !onThisMachine(brokerHost) || !Files.isRegularFile(defaultFile())) {
            return given;
        }
        return load(defaultFile(), env);
    }

    private static boolean onThisMachine(String host) {
        try {
            return host != null && java.net.InetAddress.getByName(host).isLoopbackAddress();
        } catch (java.net.UnknownHostException e) {
            return false;
        }
    }

    /**
     * @param file the credentials file of the address, or {@code null}
     * @param env  the environment
     * @return the credentials
     * @throws IOException naming the file that cannot be read or lacks a user name
     */
    public static BrokerCredentials load(Path file, Map<String, String> env) throws IOException {
        if (file != null) {
            Properties p = new Properties();
            try (Reader r = Files.newBufferedReader(file, StandardCharsets.UTF_8)) {
                p.load(r);
            } catch (IOException e) {
                throw new IOException("cannot read the MQTT credentials file " + file + ": " + e.getMessage(), e);
            }
            String user = p.getProperty("username");
            if (user == null || user.isBlank()) {
                throw new IOException("the MQTT credentials file " + file + " has no 'username=' line");
            }
            warnIfReadableByOthers(file);
            String password = p.getProperty("password");
            return new BrokerCredentials(user.strip(), password == null ? null : password.getBytes(StandardCharsets.UTF_8));
        }
        String user = env.get(USERNAME_ENV);
        if (user == null || user.isBlank()) {
            return NONE;
        }
        String password = env.get(PASSWORD_ENV);
        String passwordFile = env.get(PASSWORD_FILE_ENV);
        if (password == null && passwordFile != null && !passwordFile.isBlank()) {
            Path pf = Path.of(passwordFile);
            try {
                password = Files.readString(pf, StandardCharsets.UTF_8).strip();
            } catch (IOException e) {
                throw new IOException("cannot read the MQTT password file " + pf + " (" + PASSWORD_FILE_ENV + "): " + e.getMessage(), e);
            }
            warnIfReadableByOthers(pf);
        }
        return new BrokerCredentials(user, password == null ? null : password.getBytes(StandardCharsets.UTF_8));
    }

    @Override
    public String toString() {
        return username == null ? "anonymous" : "user " + username + (password == null ? " without password" : " with a password");
    }

    private static void warnIfReadableByOthers(Path file) {
        try {
            Set<PosixFilePermission> perms = Files.getPosixFilePermissions(file);
            if (perms.contains(PosixFilePermission.OTHERS_READ) || perms.contains(PosixFilePermission.GROUP_READ)) {
                org.slf4j.LoggerFactory.getLogger(BrokerCredentials.class)
                        .warn("{} holds an MQTT password and others may read it; chmod 600 {}", file, file);
            }
        } catch (IOException | UnsupportedOperationException e) {
            // not a POSIX file system: nothing to check
        }
    }
}
