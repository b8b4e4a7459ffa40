package io.robomw.config.description;

import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.api.spi.SecretRef;
import io.robomw.config.yaml.MappingReader;

import java.net.URI;
import java.net.URISyntaxException;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;

/**
 * Reads the optional {@code messaging:} and {@code agency:} sections of a robot file: how the
 * robot's communication component and agency start (docs/robot-yaml.md). Secrets are named by
 * reference only ({@code password_file}, {@code password_env}, {@code key_file}, {@code key_env});
 * a secret written into the file is refused, so robot files can be shared and checked in.
 * Relative file names are resolved against the robot file's directory.
 */
final class ComponentSections {

    private final String robotName;
    private final String source;
    private final Path base;

    ComponentSections(String robotName, String source) {
        this.robotName = robotName.isEmpty() ? "robot" : robotName;
        this.source = source;
        Path parent = Path.of(source).toAbsolutePath().getParent();
        this.base = parent == null ? Path.of("").toAbsolutePath() : parent;
    }

    MessagingConfig messaging(Optional<MappingReader> section) {
        if (section.isEmpty()) {
            return MessagingConfig.defaults(robotName, source);
        }
        MappingReader m = section.get();
        String name = m.text("name").orElse(robotName);
        if (name.isBlank()) {
            m.problem("name", "must not be empty");
            name = robotName;
        }
        List<String> listen = addresses(m, "listen");
        List<String> connect = addresses(m, "connect");
        Map<String, SecretRef> passwords = new LinkedHashMap<>();
        m.mapping("topics").ifPresent(topics -> {
            for (String topic : topics.keys()) {
                topics.mapping(topic).ifPresent(t -> {
                    secret(t, "password", "the topic's password").ifPresent(ref -> passwords.put(topic, ref));
                    t.finish();
                });
            }
            topics.finish();
        });
        m.finish();
        return new MessagingConfig(name, listen, connect, passwords, source);
    }

    AgencyConfig agency(Optional<MappingReader> section) {
        AgencyConfig defaults = AgencyConfig.defaults(robotName, source);
        if (section.isEmpty()) {
            return defaults;
        }
        MappingReader m = section.get();
        String homeName = m.text("home_name").orElse(defaults.homeName());
        if (!homeName.matches("[A-Za-z0-9._-]+")) {
            m.problem("home_name", "must be a host name of letters, digits, '.', '_' and '-', got '" + homeName + "'");
            homeName = defaults.homeName();
        }
        String bind = m.text("bind").orElse(defaults.bind());
        int port = m.integer("port", 0);
        if (port < 0 || port > 65_535) {
            m.problem("port", "must be 0 (any free port) to 65535, got " + port);
            port = 0;
        }
        Optional<SecretRef> key = secret(m, "key", "the cluster passphrase");
        m.finish();
        return new AgencyConfig(homeName, bind, port, key, source);
    }

    /** Reads {@code PREFIX_file} or {@code PREFIX_env}; refuses {@code PREFIX} itself (an inline secret). */
    private Optional<SecretRef> secret(MappingReader m, String prefix, String what) {
        if (m.has(prefix)) {
            m.problem(prefix, "never write a secret into a robot file: give " + prefix + "_file: FILE (a file holding "
                    + what + ") or " + prefix + "_env: VARIABLE (an environment variable holding it)");
        }
        Optional<String> file = m.text(prefix + "_file");
        Optional<String> env = m.text(prefix + "_env");
        if (file.isPresent() && env.isPresent()) {
            m.problem(prefix + "_env", "give " + prefix + "_file or " + prefix + "_env, not both");
            return Optional.empty();
        }
        if (file.isPresent()) {
            return Optional.of(new SecretRef(SecretRef.Kind.FILE, base.resolve(file.get()).normalize().toString(), source));
        }
        if (env.isPresent()) {
            if (!env.get().matches("[A-Za-z_][A-Za-z0-9_]*")) {
                m.problem(prefix + "_env", "must be the name of an environment variable, got '" + env.get() + "'");
                return Optional.empty();
            }
            return Optional.of(new SecretRef(SecretRef.Kind.ENVIRONMENT, env.get(), source));
        }
        if (prefix.equals("password") && !m.has(prefix)) {
            m.problem(prefix + "_file", "missing: a protected topic needs password_file: FILE or password_env: VARIABLE");
        }
        return Optional.empty();
    }

    private static List<String> addresses(MappingReader m, String key) {
        List<String> out = m.textList(key);
        for (String a : out) {
            String why = addressProblem(a);
            if (why != null) {
                m.problem(key, "'" + a + "' is not a messaging address: " + why);
            }
        }
        return out;
    }

    private static String addressProblem(String address) {
        try {
            URI u = new URI(address);
            if (u.getScheme() == null) {
                return "it needs a scheme, as in tcp://127.0.0.1:7000, udp://..., multicast://239.1.2.3:7000 or rmi://host:port/name";
            }
            if (u.getHost() == null || u.getPort() < 0) {
                return "it needs a host and a port, as in " + u.getScheme() + "://127.0.0.1:7000 (port 0 picks a free one)";
            }
            return null;
        } catch (URISyntaxException e) {
            return e.getMessage();
        }
    }
}
