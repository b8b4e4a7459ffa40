package io.robomw.cli.broker;

import java.io.IOException;
import java.io.Reader;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.nio.file.FileAlreadyExistsException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermission;
import java.nio.file.attribute.PosixFilePermissions;
import java.security.MessageDigest;
import java.security.SecureRandom;
import java.util.Base64;
import java.util.Properties;
import java.util.Set;

/**
 * The one user of {@code mw broker} (as Mosquitto 2.0 refuses anonymous clients until it has a
 * password file): its name and password, kept in a credentials file only its owner can read
 * (mode 600, in a folder of mode 700), in the format every {@code mw} command reads with
 * {@code credentials=FILE} (Java properties: {@code username=...}, {@code password=...}). On
 * first start the file is generated with a random password, which is printed once.
 *
 * @param name      the user name
 * @param password  the password
 * @param file      where it is kept
 * @param generated whether this start generated it
 */
public record BrokerUser(String name, String password, Path file, boolean generated) {

    /** The user name of a generated file. */
    public static final String DEFAULT_NAME = "robomw";

    /**
     * Reads the credentials file, or generates it if it does not exist.
     *
     * @param file the credentials file
     * @return the user
     * @throws IOException naming the file if it cannot be read, lacks a name or password, or may be read by others
     */
    public static BrokerUser loadOrGenerate(Path file) throws IOException {
        if (!Files.exists(file)) {
            try {
                return generate(file);
            } catch (FileAlreadyExistsException e) {
                // another broker made it meanwhile: read that one
            }
        }
        Properties p = new Properties();
        try (Reader r = Files.newBufferedReader(file, StandardCharsets.UTF_8)) {
            p.load(r);
        } catch (IOException e) {
            throw new IOException("cannot read the broker's credentials file " + file + ": " + e.getMessage(), e);
        }
        String name = p.getProperty("username");
        String password = p.getProperty("password");
        if (name == null || name.isBlank() || password == null || password.isBlank()) {
            throw new IOException("the broker's credentials file " + file + " needs 'username=' and 'password=' lines");
        }
        try {
            Set<PosixFilePermission> perms = Files.getPosixFilePermissions(file);
            if (perms.contains(PosixFilePermission.OTHERS_READ) || perms.contains(PosixFilePermission.GROUP_READ)) {
                throw new IOException("the broker's credentials file " + file + " may be read by other users: chmod 600 " + file);
            }
        } catch (UnsupportedOperationException e) {
            // not a POSIX file system: nothing to check
        }
        return new BrokerUser(name.strip(), password.strip(), file, false);
    }

    private static BrokerUser generate(Path file) throws IOException {
        Path dir = file.toAbsolutePath().getParent();
        if (!Files.isDirectory(dir)) {
            Files.createDirectories(dir, PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString("rwx------")));
        }
        byte[] secret = new byte[24];
        new SecureRandom().nextBytes(secret);
        String password = Base64.getUrlEncoder().withoutPadding().encodeToString(secret);
        String text = "# the user of mw broker (generated); mw commands read it for brokers on this machine\n"
                + "username=" + DEFAULT_NAME + "\npassword=" + password + "\n";
        Files.createFile(file, PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString("rw-------")));
        Files.writeString(file, text, StandardCharsets.UTF_8);
        return new BrokerUser(DEFAULT_NAME, password, file, true);
    }

    /**
     * @param user     the user name a client gave, or {@code null}
     * @param password the password it gave, or {@code null}
     * @return whether they are this user's (the password compared in constant time)
     */
    boolean admits(String user, ByteBuffer password) {
        if (user == null || password == null || !user.equals(name)) {
            return false;
        }
        byte[] given = new byte[password.remaining()];
        password.duplicate().get(given);
        return MessageDigest.isEqual(given, this.password.getBytes(StandardCharsets.UTF_8));
    }

    @Override
    public String toString() {
        return "user " + name + " (" + file + ")";
    }
}
