package io.robomw.cli;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.api.Message;
import picocli.CommandLine.Command;
import picocli.CommandLine.Option;

import java.nio.file.Path;
import java.util.HexFormat;
import java.util.Locale;

/**
 * {@code mw msg pub|sub|send}: messaging by hand, like {@code ros2 topic pub/echo}. Each
 * subcommand is its own class; this one holds what they share.
 */
@Command(name = "msg", mixinStandardHelpOptions = true, description = "Publish, subscribe, send and echo messages by hand (tcp, udp, multicast, rmi, mqtt).",
        subcommands = {MsgPubCommand.class, MsgSubCommand.class, MsgSendCommand.class, MsgEchoCommand.class})
final class MsgCommand {

    /** Options every msg subcommand has. */
    static final class Common {
        @Option(names = "--password-file", paramLabel = "FILE", description = "file holding the topic's password (messages signed, payloads encrypted);"
                + " default: the " + Secrets.TOPIC_PASSWORD_ENV + " environment variable, else an open topic")
        Path passwordFile;

        /** Refused: a secret on the command line shows in ps. */
        @Option(names = "--password", hidden = true, converter = Secrets.RefusedTopicPassword.class)
        String refusedPassword;

        @Option(names = "--name", description = "this node's name (default: ${DEFAULT-VALUE})", defaultValue = "mw-msg")
        String name;

        @Option(names = "--tls-keystore", description = "PKCS#12 key store: turns on mutual TLS for tcp and rmi")
        Path keyStore;

        @Option(names = "--tls-truststore", description = "PKCS#12 store of the peers to trust (with --tls-keystore)")
        Path trustStore;

        @Option(names = "--tls-password-file", paramLabel = "FILE", description = "file holding the password of both stores (default: the "
                + Secrets.TLS_PASSWORD_ENV + " environment variable, else none)")
        Path storePasswordFile;

        /** Refused: a secret on the command line shows in ps. */
        @Option(names = "--tls-password", hidden = true, converter = Secrets.RefusedTlsPassword.class)
        String refusedStorePassword;

        /** @return the topic's password, from the file or the environment; {@code null} for an open topic */
        String password() {
            return Secrets.read(passwordFile, "--password-file", Secrets.TOPIC_PASSWORD_ENV).orElse(null);
        }

        @Option(names = "--max-connections", paramLabel = "N", defaultValue = "128",
                description = "connections a bound address accepts at once; one more is refused, told why (default ${DEFAULT-VALUE})")
        int maxConnections;

        MessagingSettings settings() {
            MessagingSettings s = MessagingSettings.defaults();
            s = s.withLimits(s.limits().withMaxConnections(maxConnections));
            if (keyStore != null) {
                String storePassword = Secrets.read(storePasswordFile, "--tls-password-file", Secrets.TLS_PASSWORD_ENV).orElse("");
                s = s.withTls(new TlsSettings(keyStore, storePassword, trustStore == null ? keyStore : trustStore, storePassword));
            }
            return s;
        }
    }

    private MsgCommand() {
    }

    /**
     * @param address an address
     * @return whether a node joins it (multicast) rather than connecting or binding
     */
    static boolean isGroup(String address) {
        return Address.parse(address).scheme().equals("multicast");
    }

    /**
     * @param m a message
     * @return one line for the terminal
     */
    static String describe(Message m) {
        return String.format(Locale.ROOT, "[%s] %s %s: %s", m.topic(), m.sender(), m.function(), payloadText(m.payload()));
    }

    private static String payloadText(Object payload) {
        if (payload instanceof byte[] bytes) {
            return bytes.length + " bytes " + HexFormat.of().formatHex(bytes, 0, Math.min(bytes.length, 32)) + (bytes.length > 32 ? "..." : "");
        }
        return String.valueOf(payload);
    }

    /** Builds a node that binds or joins {@code address}. */
    static MessagingNode bound(Common c, String address) {
        return MessagingNode.builder(c.name).settings(c.settings()).bind(address).build();
    }
}
