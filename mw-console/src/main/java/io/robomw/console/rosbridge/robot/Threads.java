package io.robomw.console.rosbridge.robot;

import io.robomw.api.spi.FailurePolicy;

import java.util.concurrent.ExecutorService;
import java.util.concurrent.ScheduledExecutorService;

/**
 * The threads the bridge samples and drives its robots on, and the policy their failures go to.
 *
 * @param feeds    runs the periodic samples (odometry, sensors, /tf); a sample never blocks it
 * @param blocking runs calls that wait for a network (a remote robot's pose or drive, a stop)
 * @param failures where a sample's or a call's unexpected failure is reported
 */
public record Threads(ScheduledExecutorService feeds, ExecutorService blocking, FailurePolicy failures) {
}
