package io.robomw.agents.messaging.robot;

import io.robomw.agents.components.RobotAgency;
import io.robomw.agents.host.ClusterKeyLookup;
import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.RobotFactory;
import io.robomw.api.spi.SecretRef;

import java.net.URI;
import java.security.SecureRandom;

/**
 * Opens robots served by other processes for {@code Robots.remote(address)}:
 * {@code tcp://host:port/robot}, {@code rmi://host:port/name[/robot]} (the robot defaults to the
 * RMI name), or through a broker {@code mqtt://broker:port[/prefix]/robot} and {@code mqtts://...}
 * (the last path level is the robot, the levels before it the topic prefix; the address's options
 * apply to the broker session). The robot topic's password comes from the file named by
 * {@code ?password-file=FILE}, else the environment variable {@value #PASSWORD_ENV}; a password
 * in the address itself ({@code ?password=...}) is refused, since addresses show in process lists
 * and logs. Mutual TLS is given as {@link MessagingSettings} in the {@link PlatformServices}.
 * Each remote robot gets its own messaging node and agency (an in-process home, started on first
 * use: {@link RobotAgency}; an {@link AgencyConfig} in the {@link PlatformServices} says how), closed with it.
 */
public abstract class RemoteRobotFactory implements RobotFactory {

    /** Environment variable holding the robot topic's password when the address names no password file. */
    public static final String PASSWORD_ENV = "MW_ROBOT_PASSWORD";
    /** The address option naming the file that holds the robot topic's password. */
    public static final String PASSWORD_FILE_OPTION = "password-file";

    private final String scheme;

    /** @param scheme the scheme this factory opens */
    protected RemoteRobotFactory(String scheme) {
        this.scheme = scheme;
    }

    @Override
    public String scheme() {
        return scheme;
    }

    @Override
    public Robot open(URI location, PlatformServices services) {
        Address a = Address.parse(location.toString());
        if (a.query().containsKey("password")) {
            throw new RobotException("'" + a.endpoint() + (a.path().isEmpty() ? "" : "/" + a.path()) + "': a password in the address is refused (addresses show in process lists and logs);"
                    + " put it in a file only you can read and add ?" + PASSWORD_FILE_OPTION + "=FILE, or set " + PASSWORD_ENV);
        }
        String password = password(a);
        String[] path = a.path().split("/");
        if (a.path().isEmpty()) {
            throw new RobotException("'" + location + "' names no robot: use " + scheme + "://host:port/robot-name");
        }
        String host;
        String robot;
        if (scheme.equals("rmi")) {
            host = a.withPath(path[0]).toString();
            robot = path.length > 1 ? path[1] : path[0];
        } else if (scheme.equals("mqtt") || scheme.equals("mqtts")) {
            robot = path[path.length - 1];
            host = brokerAddress(a, String.join("/", java.util.Arrays.copyOf(path, path.length - 1)));
        } else {
            host = a.endpoint();
            robot = path[0];
        }
        MessagingSettings settings = RobotProtocol.forClient(services.find(MessagingSettings.class).orElse(MessagingSettings.defaults()));
        // a name of its own each time: a replay window kept on disk under it would never be read again
        MessagingNode node = MessagingNode.builder("remote-" + robot + "-" + Long.toHexString(new SecureRandom().nextLong()).substring(0, 6))
                .settings(settings).replayDirectory(null).build();
        AgencyConfig agencyConfig = services.find(AgencyConfig.class).orElse(AgencyConfig.defaults(robot, location.toString()));
        RobotAgency agency = new RobotAgency(agencyConfig, ClusterKeyLookup.ofThisProcess());
        try {
            return new RemoteRobot(node, true, host, robot, password, agency);
        } catch (RuntimeException e) {
            agency.close();
            node.close();
            throw e;
        }
    }

    /** @return the robot topic's password: from the address's password file, else the environment; {@code null} for none */
    private static String password(Address a) {
        String file = a.query().get(PASSWORD_FILE_OPTION);
        try {
            if (file != null) {
                return new SecretRef(SecretRef.Kind.FILE, file, "the address's " + PASSWORD_FILE_OPTION).read(System::getenv);
            }
            String env = System.getenv(PASSWORD_ENV);
            return env == null ? null : new SecretRef(SecretRef.Kind.ENVIRONMENT, PASSWORD_ENV, "the environment").read(System::getenv);
        } catch (IllegalStateException e) {
            throw new RobotException(e.getMessage(), e);
        }
    }

    /** The broker address of a remote robot's address: its prefix, and its options but the robot topic's password file. */
    private static String brokerAddress(Address a, String prefix) {
        StringBuilder b = new StringBuilder(a.endpoint());
        if (!prefix.isEmpty()) {
            b.append('/').append(prefix);
        }
        char sep = '?';
        for (var e : a.query().entrySet()) {
            if (!e.getKey().equals(PASSWORD_FILE_OPTION)) {
                b.append(sep).append(e.getKey()).append('=').append(e.getValue());
                sep = '&';
            }
        }
        return b.toString();
    }

    /** {@code mqtt://broker:port[/prefix]/robot}. */
    public static final class Mqtt extends RemoteRobotFactory {
        /** For {@link java.util.ServiceLoader}. */
        public Mqtt() {
            super("mqtt");
        }
    }

    /** {@code mqtts://broker:port[/prefix]/robot}. */
    public static final class Mqtts extends RemoteRobotFactory {
        /** For {@link java.util.ServiceLoader}. */
        public Mqtts() {
            super("mqtts");
        }
    }

    /** {@code tcp://host:port/robot}. */
    public static final class Tcp extends RemoteRobotFactory {
        /** For {@link java.util.ServiceLoader}. */
        public Tcp() {
            super("tcp");
        }
    }

    /** {@code rmi://host:port/name[/robot]}. */
    public static final class Rmi extends RemoteRobotFactory {
        /** For {@link java.util.ServiceLoader}. */
        public Rmi() {
            super("rmi");
        }
    }
}
