package io.robomw.api.spi;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.Objects;
import java.util.function.Function;

/**
 * Where a secret (a topic password, a cluster passphrase) is kept: a file or an environment
 * variable, never the secret itself. Robot files name secrets this way so that they can be
 * shared and checked in without them.
 *
 * @param kind      where to look
 * @param reference the file's path (resolved against the robot file's directory when relative)
 *                  or the variable's name
 * @param source    the file that named it, for error messages
 */
public record SecretRef(Kind kind, String reference, String source) {

    /** Where a secret is kept. */
    public enum Kind {
        /** In a file; surrounding white space is ignored. */
        FILE,
        /** In an environment variable. */
        ENVIRONMENT
    }

    /** Checks the values. */
    public SecretRef {
        Objects.requireNonNull(kind, "kind");
        Objects.requireNonNull(source, "source");
        if (reference == null || reference.isBlank()) {
            throw new IllegalArgumentException(source + ": a secret reference must name a file or an environment variable");
        }
    }

    /**
     * Reads the secret.
     *
     * @param environment how to look up an environment variable ({@code System::getenv} in production)
     * @return the secret, without surrounding white space
     * @throws IllegalStateException naming the robot file and the reference if it cannot be read or is empty
     */
    public String read(Function<String, String> environment) {
        String value;
        if (kind == Kind.FILE) {
            Path file = Path.of(reference);
            try {
                value = Files.readString(file, StandardCharsets.UTF_8);
            } catch (NoSuchFileException e) {
                throw new IllegalStateException(source + ": the secret file " + file.toAbsolutePath() + " does not exist", e);
            } catch (IOException e) {
                throw new IllegalStateException(source + ": cannot read the secret file " + file + ": " + e.getMessage(), e);
            }
        } else {
            value = environment.apply(reference);
            if (value == null) {
                throw new IllegalStateException(source + ": the environment variable " + reference + " that should hold a secret is not set");
            }
        }
        if (value.isBlank()) {
            throw new IllegalStateException(source + ": the secret in " + this + " is empty");
        }
        return value.strip();
    }

    @Override
    public String toString() {
        return kind == Kind.FILE ? "file " + reference : "environment variable " + reference;
    }
}
