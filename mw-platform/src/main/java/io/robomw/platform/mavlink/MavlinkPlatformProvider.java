package io.robomw.platform.mavlink;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.api.spi.SecretRef;
import io.robomw.platform.command.HighLevelRobotPlatform;
import io.robomw.platform.mavlink.gcs.GroundStation;
import io.robomw.platform.mavlink.gcs.MavlinkVehicle;
import io.robomw.platform.mavlink.link.MavlinkEndpoint;
import io.robomw.platform.mavlink.link.MavlinkLink;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.SignatureCheck;
import io.robomw.platform.mavlink.wire.Signer;
import io.robomw.platform.mavlink.wire.SigningKey;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.time.InstantSource;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;

/**
 * {@code platform: mavlink}: a drone, boat or rover flown by ArduPilot or PX4, driven by RoboMW as
 * a MAVLink 2 ground station (docs/vehicles.md). It moves by the high-level commands of its
 * description's vehicle drive ({@code takeoff}, {@code land}, {@code move}, {@code turn},
 * {@code arc}, {@code drive}, {@code climb}), and reads its sensors from its telemetry.
 *
 * <p>Connection keys:
 * <ul>
 *   <li>{@code link}: where the vehicle is, as MAVSDK writes it: {@code udpin://HOST:PORT} (listen;
 *   the default is {@value #DEFAULT_LINK}, this machine only, where SITL's {@code --out} sends;
 *   {@code udpin://0.0.0.0:14550} listens on every interface, for a radio bridge or a vehicle on the
 *   network, and is logged as a warning without signing),
 *   {@code udpout://HOST:PORT}, {@code serial:///dev/ttyUSB0:57600};</li>
 *   <li>{@code system_id}, {@code component_id}: this ground station's (default 255 and 190, as
 *   MAVProxy and Mission Planner);</li>
 *   <li>{@code vehicle_system_id}: the vehicle to drive (default: the first heard);</li>
 *   <li>{@code connect_timeout_ms}: how long opening waits for the vehicle's HEARTBEAT (default
 *   {@value #DEFAULT_CONNECT_MS});</li>
 *   <li>{@code signing_key_file} or {@code signing_key_env}: a file (relative to the robot file)
 *   or an environment variable holding a passphrase whose SHA-256 is the signing key, as
 *   MAVProxy's {@code signing setup} makes it; never the key itself in the file. With a key every
 *   frame is signed and the vehicle's frames must be; {@code signing_link_id} (default 0).</li>
 * </ul>
 */
public final class MavlinkPlatformProvider implements PlatformProvider {

    private static final Logger LOG = LoggerFactory.getLogger(MavlinkPlatformProvider.class);

    /**
     * The default link: listen on the ground station port every MAVLink tool knows, on loopback
     * (where SITL's default {@code --out} sends); a vehicle elsewhere needs the address named.
     */
    public static final String DEFAULT_LINK = "udpin://127.0.0.1:14550";
    /** Connection keys that would hold a signing secret inline: refused, naming the keys to use. */
    private static final List<String> INLINE_SECRETS = List.of("signing_key", "signing_passphrase", "signing_secret");
    /** Default {@code connect_timeout_ms}. */
    public static final int DEFAULT_CONNECT_MS = 10_000;

    @Override
    public String platformName() {
        return "mavlink";
    }

    @Override
    public List<String> check(PlatformConfig config) {
        List<String> problems = new ArrayList<>();
        try {
            MavlinkEndpoint.parse(config.connection().text("link").orElse(DEFAULT_LINK));
        } catch (IllegalArgumentException e) {
            problems.add(config.source() + ": connection.link: " + e.getMessage());
        }
        if (!config.motors().isEmpty()) {
            problems.add(config.source() + ": a MAVLink vehicle moves by its autopilot's targets; it has no motor ports for the robot file to"
                    + " drive (found " + config.motorPorts() + "): give it a vehicle drive and no wheels or actuators");
        }
        if (config.connection().text("signing_key_file").isPresent() && config.connection().text("signing_key_env").isPresent()) {
            problems.add(config.source() + ": give connection.signing_key_file or connection.signing_key_env, not both");
        }
        for (String inline : INLINE_SECRETS) {
            if (config.connection().text(inline).isPresent()) {
                problems.add(config.source() + ": connection." + inline + " is not taken: a secret does not go in a robot file; put the signing"
                        + " passphrase in a file only you can read and give connection.signing_key_file, or name an environment variable"
                        + " with connection.signing_key_env");
            }
        }
        problems.addAll(MavlinkVehicle.checkSensors(config.sensors(), config.source()));
        return problems;
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        List<String> problems = check(config);
        if (!problems.isEmpty()) {
            throw new IOException(String.join("; ", problems));
        }
        MavlinkEndpoint endpoint = MavlinkEndpoint.parse(config.connection().text("link").orElse(DEFAULT_LINK));
        FrameEncoder encoder = new FrameEncoder(config.connection().integer("system_id", 255), config.connection().integer("component_id", 190));
        SignatureCheck check = null;
        Optional<SigningKey> key = signingKey(config);
        if (key.isPresent()) {
            encoder.signWith(new Signer(key.get(), config.connection().integer("signing_link_id", 0), InstantSource.system()));
            check = new SignatureCheck(key.get(), InstantSource.system());
        }
        if (key.isEmpty() && !endpoint.local()) {
            LOG.warn("robot '{}' ({}): the MAVLink link {} reaches beyond this machine and is not signed: anyone on that network can command"
                    + " the vehicle; give connection.signing_key_file (docs/security.md)", config.robotName(), config.source(), endpoint);
        }
        MavlinkLink link = endpoint.open(System::nanoTime);
        GroundStation gcs = new GroundStation(config.robotName(), link, encoder, check, config.connection().integer("vehicle_system_id", 0),
                System::nanoTime, config.failures());
        try {
            return MavlinkVehicle.open(config, gcs, Duration.ofMillis(config.connection().integer("connect_timeout_ms", DEFAULT_CONNECT_MS)));
        } catch (IOException | RuntimeException e) {
            gcs.close();
            throw e;
        }
    }

    private static Optional<SigningKey> signingKey(PlatformConfig config) {
        Optional<SecretRef> ref = config.connection().text("signing_key_file")
                .map(f -> new SecretRef(SecretRef.Kind.FILE, resolve(config.source(), f), config.source()))
                .or(() -> config.connection().text("signing_key_env").map(v -> new SecretRef(SecretRef.Kind.ENVIRONMENT, v, config.source())));
        return ref.map(r -> SigningKey.fromPassphrase(r.read(System::getenv)));
    }

    private static String resolve(String robotFile, String file) {
        Path p = Path.of(file);
        if (p.isAbsolute()) {
            return file;
        }
        Path dir = Path.of(robotFile).toAbsolutePath().getParent();
        return dir == null ? file : dir.resolve(p).toString();
    }
}
