package io.robomw.platform.mavlink.gcs;

import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.command.HighLevelRobotPlatform;

import java.io.IOException;
import java.time.Duration;
import java.util.List;

/**
 * Puts a MAVLink vehicle's platform together: the ground station on its link, waiting for the
 * vehicle's HEARTBEAT; the command and sensor platforms; the execution action thread
 * ({@link HighLevelRobotPlatform}), told when the link is lost and restored.
 */
public final class MavlinkVehicle {

    private static final org.slf4j.Logger LOG = org.slf4j.LoggerFactory.getLogger(MavlinkVehicle.class);
    /** How long opening waits for the vehicle's first local position, after its HEARTBEAT. */
    static final Duration POSITION_WAIT = Duration.ofSeconds(3);

    private MavlinkVehicle() {
    }

    /**
     * @param sensors a description's sensors
     * @param source  the robot file
     * @return one problem per sensor port a vehicle does not have
     */
    public static List<String> checkSensors(List<SensorChannel> sensors, String source) {
        return VehicleSensorPlatform.check(sensors, source);
    }

    /**
     * Starts the ground station, waits for the vehicle, and builds the platform.
     *
     * @param config  the robot's configuration
     * @param gcs     the ground station, not started (closed with the platform)
     * @param connect how long to wait for the vehicle's HEARTBEAT
     * @return the running platform
     * @throws IOException naming the link when no vehicle is heard in time
     */
    public static MavlinkPlatform open(PlatformConfig config, GroundStation gcs, Duration connect) throws IOException {
        Relay relay = new Relay();
        gcs.start(relay);
        gcs.awaitVehicle(connect);
        if (!gcs.awaitPosition(POSITION_WAIT)) {
            LOG.warn("robot '{}': the vehicle on {} reports no local position (LOCAL_POSITION_NED) yet: no position fix? Motions fail"
                    + " until it does", config.robotName(), gcs.describe());
        }
        VehicleCommandPlatform commands = new VehicleCommandPlatform(config.robotName(), config.clock(), gcs);
        VehicleSensorPlatform sensors = new VehicleSensorPlatform(config.robotName(), gcs);
        HighLevelRobotPlatform platform = new HighLevelRobotPlatform(config, commands, sensors, gcs);
        relay.to(commands, platform, gcs.describe());
        return new MavlinkPlatform(platform.start(), gcs);
    }

    /** Passes the ground station's events on, once the platform exists. */
    private static final class Relay implements GroundStation.Listener {
        private volatile VehicleCommandPlatform commands;
        private volatile HighLevelRobotPlatform platform;
        private volatile String link;

        void to(VehicleCommandPlatform c, HighLevelRobotPlatform p, String l) {
            link = l;
            platform = p;
            commands = c;
        }

        @Override
        public void tick(long nowNanos) {
            VehicleCommandPlatform c = commands;
            if (c != null) {
                c.tick(nowNanos);
            }
        }

        @Override
        public void lost(RobotLinkException cause) {
            VehicleCommandPlatform c = commands;
            if (c != null) {
                c.lost(cause);
                platform.linkFailed(link, cause);
            }
        }

        @Override
        public void restored() {
            HighLevelRobotPlatform p = platform;
            if (p != null) {
                commands.restored();
                p.linkRestored();
            }
        }
    }
}
