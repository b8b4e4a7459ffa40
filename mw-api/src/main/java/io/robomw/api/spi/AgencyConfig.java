package io.robomw.api.spi;

import java.util.Objects;
import java.util.Optional;

/**
 * How a robot's agency (sending mobile agents) is set up: the optional {@code agency:} section of
 * its robot file, or the defaults. Agents sent from a robot have an in-process home: a small agent
 * host, without a robot, that starts on first use and where their reports and results arrive.
 *
 * <p>The cluster key the home proves to other hosts comes from {@link #clusterKey()} when given,
 * else from the environment variable {@value #KEY_VARIABLE}, else from the file
 * {@code ~/.robomw/cluster.key} ({@link #DEFAULT_KEY_FILE}).
 *
 * @param homeName   the home's name (by default {@code ROBOT-home})
 * @param bind       the address its RMI endpoint listens on (by default {@code 127.0.0.1})
 * @param port       its RMI port; 0 (the default) picks a free one
 * @param clusterKey where the cluster passphrase is kept, if the robot file says
 * @param source     where the settings came from (the robot file), for messages
 */
public record AgencyConfig(String homeName, String bind, int port, Optional<SecretRef> clusterKey, String source) {

    /** The environment variable that holds the cluster passphrase when the robot file names none. */
    public static final String KEY_VARIABLE = "MW_CLUSTER_KEY";
    /** The file that holds it when neither the robot file nor the environment do, under the user's home. */
    public static final String DEFAULT_KEY_FILE = ".robomw/cluster.key";

    /** Checks the values. */
    public AgencyConfig {
        Objects.requireNonNull(source, "source");
        Objects.requireNonNull(clusterKey, "clusterKey");
        if (homeName == null || !homeName.matches("[A-Za-z0-9._-]+")) {
            throw new IllegalArgumentException(source + ": agency.home_name '" + homeName + "' is not a host name: use letters, digits, '.', '_' and '-'");
        }
        if (bind == null || bind.isBlank()) {
            throw new IllegalArgumentException(source + ": agency.bind must name an address");
        }
        if (port < 0 || port > 65_535) {
            throw new IllegalArgumentException(source + ": agency.port must be 0 to 65535, got " + port);
        }
    }

    /**
     * @param robotName the robot's name
     * @param source    its file
     * @return the settings of a robot whose file has no {@code agency:} section
     */
    public static AgencyConfig defaults(String robotName, String source) {
        return new AgencyConfig(robotName.replaceAll("[^A-Za-z0-9._-]", "_") + "-home", "127.0.0.1", 0, Optional.empty(), source);
    }
}
