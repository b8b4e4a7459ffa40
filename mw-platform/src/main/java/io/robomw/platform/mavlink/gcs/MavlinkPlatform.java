package io.robomw.platform.mavlink.gcs;

import io.robomw.api.Clock;
import io.robomw.api.Pose;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.PoseSource;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.command.HighLevelRobotPlatform;

import java.util.Optional;
import java.util.concurrent.CompletableFuture;

/**
 * A MAVLink vehicle's running platform: the Platform Layer's {@link HighLevelRobotPlatform} (the
 * execution action thread and the vehicle's command and sensor platforms), which also says where
 * the vehicle is from its telemetry ({@link PoseSource}): LOCAL_POSITION_NED's north and east as y
 * and x, ATTITUDE's yaw (clockwise from north) as a heading anti-clockwise from east, and the
 * altitude above its origin as z.
 */
public final class MavlinkPlatform implements RobotPlatform, HighLevelPlatform, PoseSource {

    private final HighLevelRobotPlatform platform;
    private final GroundStation gcs;

    MavlinkPlatform(HighLevelRobotPlatform platform, GroundStation gcs) {
        this.platform = platform;
        this.gcs = gcs;
    }

    /** @return the ground station on the vehicle's link (its telemetry, its kind) */
    public GroundStation groundStation() {
        return gcs;
    }

    @Override
    public Optional<Pose> reportedPose() {
        return gcs.telemetry().local().map(l -> new Pose(l.east(), l.north(), Math.PI / 2 - l.yaw(), -l.down()));
    }

    @Override
    public CompletableFuture<Void> execute(HighLevelCommand command) {
        return platform.execute(command);
    }

    @Override
    public Clock clock() {
        return platform.clock();
    }

    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        return platform.run(command);
    }

    @Override
    public CompletableFuture<Void> stopAll() {
        return platform.stopAll();
    }

    @Override
    public CompletableFuture<Double> readRaw(String sensorName) {
        return platform.readRaw(sensorName);
    }

    @Override
    public double motorDegrees(String port) {
        return platform.motorDegrees(port);
    }

    @Override
    public boolean hasEncoder(String port) {
        return platform.hasEncoder(port);
    }

    /** Ends every command, stops the action thread and closes the link. Idempotent. */
    @Override
    public void close() {
        platform.close();
    }
}
