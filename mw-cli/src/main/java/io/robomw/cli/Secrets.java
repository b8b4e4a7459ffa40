package io.robomw.cli;

import io.robomw.api.spi.SecretRef;
import picocli.CommandLine.ITypeConverter;
import picocli.CommandLine.TypeConversionException;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermission;
import java.util.Optional;
import java.util.Set;

/**
 * The secrets a command is given: from a file ({@code --...-file FILE}) or an environment
 * variable, never from an option's value, which every user of the machine sees in {@code ps}
 * (as Mosquitto's and SROS2's tools do). The options that used to take a secret as their value
 * are refused, saying what to use instead.
 */
final class Secrets {

    /** Environment variable of the password callers of {@code mw host --serve} must give. */
    static final String SERVE_PASSWORD_ENV = "MW_SERVE_PASSWORD";
    /** Environment variable of the password of the TLS key and trust stores. */
    static final String TLS_PASSWORD_ENV = "MW_TLS_PASSWORD";
    /** Environment variable of the topic password of {@code mw msg}. */
    static final String TOPIC_PASSWORD_ENV = "MW_TOPIC_PASSWORD";
    /** Environment variable of the MAVLink signing passphrase of {@code mw emulate mavlink}. */
    static final String MAVLINK_SIGNING_ENV = "MW_MAVLINK_SIGNING_KEY";

    private Secrets() {
    }

    /**
     * @param file     the file the option named, or {@code null}
     * @param option   the option's name, for messages
     * @param variable the environment variable to read when no file is given
     * @return the secret, without surrounding white space; empty when neither is given
     * @throws IllegalStateException naming the file or variable if it cannot be read or is empty
     */
    static Optional<String> read(Path file, String option, String variable) {
        if (file != null) {
            warnIfOthersMayRead(file, option);
            return Optional.of(new SecretRef(SecretRef.Kind.FILE, file.toString(), option).read(System::getenv));
        }
        if (System.getenv(variable) != null) {
            return Optional.of(new SecretRef(SecretRef.Kind.ENVIRONMENT, variable, "the environment").read(System::getenv));
        }
        return Optional.empty();
    }

    private static void warnIfOthersMayRead(Path file, String option) {
        try {
            Set<PosixFilePermission> p = Files.getPosixFilePermissions(file);
            if (p.contains(PosixFilePermission.OTHERS_READ) || p.contains(PosixFilePermission.GROUP_READ)) {
                System.err.println("mw: " + file + " (" + option + ") holds a secret and other users may read it; chmod 600 " + file);
            }
        } catch (IOException | UnsupportedOperationException e) {
            // missing (read() says so) or not a POSIX file system
        }
    }

    /** What an option that used to take a secret as its value answers now: it is refused, naming what to use instead. */
    abstract static class Refused implements ITypeConverter<String> {
        private final String option;
        private final String instead;
        private final String variable;

        Refused(String option, String instead, String variable) {
            this.option = option;
            this.instead = instead;
            this.variable = variable;
        }

        @Override
        public String convert(String value) {
            throw new TypeConversionException(option + " is no longer taken: its value shows in process lists (ps) to every user of this machine;"
                    + " put the secret in a file only you can read (chmod 600) and give " + instead + ", or set " + variable);
        }
    }

    /** {@code mw host --serve-password}. */
    static final class RefusedServePassword extends Refused {
        RefusedServePassword() {
            super("--serve-password", "--serve-password-file FILE", SERVE_PASSWORD_ENV);
        }
    }

    /** {@code --tls-password}. */
    static final class RefusedTlsPassword extends Refused {
        RefusedTlsPassword() {
            super("--tls-password", "--tls-password-file FILE", TLS_PASSWORD_ENV);
        }
    }

    /** {@code mw msg --password}. */
    static final class RefusedTopicPassword extends Refused {
        RefusedTopicPassword() {
            super("--password", "--password-file FILE", TOPIC_PASSWORD_ENV);
        }
    }

    /** {@code mw emulate mavlink --signing-key}. */
    static final class RefusedSigningKey extends Refused {
        RefusedSigningKey() {
            super("--signing-key", "--signing-key-file FILE", MAVLINK_SIGNING_ENV);
        }
    }
}
