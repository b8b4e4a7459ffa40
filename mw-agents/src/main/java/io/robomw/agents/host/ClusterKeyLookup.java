package io.robomw.agents.host;

import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.SecretRef;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Optional;
import java.util.function.Function;

/**
 * Finds the cluster key where an operator put it, in this order: a reference given explicitly
 * (a robot file's {@code agency.key_file}/{@code key_env}, or {@code --key-file}), the environment
 * variable {@value AgencyConfig#KEY_VARIABLE}, the file {@code ~/.robomw/cluster.key}. Every host
 * and every robot of a cluster must find the same passphrase.
 *
 * @param environment how environment variables are read ({@code System::getenv} in production)
 * @param userHome    the user's home directory, where the default key file lives
 */
public record ClusterKeyLookup(Function<String, String> environment, Path userHome) {

    /** @return the lookup of this process: its environment and {@code user.home} */
    public static ClusterKeyLookup ofThisProcess() {
        return new ClusterKeyLookup(System::getenv, Path.of(System.getProperty("user.home")));
    }

    /** @return where the default key file is */
    public Path defaultFile() {
        return userHome.resolve(AgencyConfig.DEFAULT_KEY_FILE);
    }

    /**
     * @param explicit a reference given explicitly, if any
     * @return the key, or empty when none of the places has one
     * @throws IOException naming the file or variable when one is named but cannot be read or is empty
     */
    public Optional<ClusterKey> find(Optional<SecretRef> explicit) throws IOException {
        if (explicit.isPresent()) {
            try {
                return Optional.of(ClusterKey.fromPassphrase(explicit.get().read(environment)));
            } catch (IllegalStateException e) {
                throw new IOException(e.getMessage(), e);
            }
        }
        String env = environment.apply(AgencyConfig.KEY_VARIABLE);
        if (env != null && !env.isBlank()) {
            return Optional.of(ClusterKey.fromPassphrase(env.strip()));
        }
        Path file = defaultFile();
        if (Files.isRegularFile(file)) {
            return Optional.of(ClusterKey.read(file));
        }
        return Optional.empty();
    }

    /**
     * @param explicit a reference given explicitly, if any
     * @param who      who needs it, for the message ("robot nxt-1's agency", "mw host")
     * @return the key
     * @throws IOException saying every place that was looked at when there is none
     */
    public ClusterKey require(Optional<SecretRef> explicit, String who) throws IOException {
        return find(explicit).orElseThrow(() -> new IOException(who + " has no cluster key: set " + AgencyConfig.KEY_VARIABLE
                + " to the cluster's passphrase, write it to " + defaultFile() + ", or name a file holding it"
                + " (--key-file FILE, or agency.key_file in a robot file); every host of a cluster must share it"));
    }
}
