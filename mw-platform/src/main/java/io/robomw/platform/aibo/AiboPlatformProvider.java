package io.robomw.platform.aibo;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.command.HighLevelRobotPlatform;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.TcpClientLink;
import io.robomw.platform.link.WireLog;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;

/**
 * {@code platform: aibo}: a Sony Aibo (ERS-7, ERS-2xx) through its URBI server over TCP. It moves
 * by the high-level commands its description's legged drive and actions give (the walking
 * functions of the dog's {@code URBI.INI}), and reads its devices by name.
 *
 * <p>Connection keys: {@code host} (the dog's address, required), {@code port} (default
 * {@value UrbiProtocol#TCP_PORT}), {@code reply_timeout_ms} (default 1000), {@code stream_ms} (how
 * often sensors are streamed, default 100; 0 reads on demand only), {@code startup} (the URBI sent
 * when a connection opens, default {@code motoron}), {@code wire_log} (a file that records every
 * byte).
 *
 * <p>Opening connects, sends the startup command and waits for its end, then streams every sensor
 * and starts the execution action thread. A lost link ends every command with
 * {@link io.robomw.api.RobotLinkException}, and is reopened in the background (the startup and the
 * streams are sent again). Closing ends the running commands with their stops, then closes the
 * link.
 */
public final class AiboPlatformProvider implements PlatformProvider {

    /** Default {@code reply_timeout_ms}. */
    public static final int DEFAULT_REPLY_TIMEOUT_MS = 1000;
    /** Default {@code stream_ms}. */
    public static final int DEFAULT_STREAM_MS = 100;
    /** How long connecting may take. */
    static final Duration CONNECT_TIMEOUT = Duration.ofSeconds(5);

    @Override
    public String platformName() {
        return "aibo";
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        String host = config.connection().text("host").orElseThrow(() -> new IOException(config.source()
                + ": the aibo platform talks URBI over TCP: give connection.host (the dog's address) and, if not " + UrbiProtocol.TCP_PORT
                + ", connection.port"));
        int port = config.connection().integer("port", UrbiProtocol.TCP_PORT);
        Duration timeout = Duration.ofMillis(config.connection().integer("reply_timeout_ms", DEFAULT_REPLY_TIMEOUT_MS));
        int streamMs = config.connection().integer("stream_ms", DEFAULT_STREAM_MS);
        if (streamMs < 0 || timeout.isNegative() || timeout.isZero()) {
            throw new IOException(config.source() + ": connection.stream_ms must be >= 0 and reply_timeout_ms > 0, got " + streamMs + " and "
                    + timeout.toMillis());
        }
        String startup = config.connection().text("startup").orElse(UrbiProtocol.DEFAULT_STARTUP);
        TcpClientLink link = new TcpClientLink(host, port, CONNECT_TIMEOUT);
        WireLog log = config.connection().text("wire_log").isPresent() ? WireLog.open(Path.of(config.connection().requireText("wire_log"))) : null;
        Communicator communicator = log == null ? new Communicator(link) : new Communicator(link, log);
        UrbiConnection connection = new UrbiConnection(config.robotName(), communicator, timeout, startup);
        try {
            connection.open();
            AiboCommandPlatform commands = new AiboCommandPlatform(config.robotName(), config.clock(), connection);
            AiboSensorPlatform sensors = new AiboSensorPlatform(config.robotName(), connection, config.clock(), Duration.ofMillis(streamMs));
            HighLevelRobotPlatform platform = new HighLevelRobotPlatform(config, commands, sensors, connection);
            connection.events(new UrbiConnection.Events() {
                @Override
                public void lost(IOException cause) {
                    platform.linkFailed(connection.describe(), cause);
                }

                @Override
                public void restored() {
                    platform.linkRestored();
                }
            });
            return platform.start();
        } catch (IOException | RuntimeException e) {
            connection.close();
            throw e;
        }
    }
}
