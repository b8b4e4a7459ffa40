package io.robomw.examples;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.api.Robots;

import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.CompletableFuture;

/**
 * Group control: one application drives several robots at once, each served by another process
 * ({@code mw host --serve tcp://127.0.0.1:7000} serves its robot), through
 * {@link Robots#remote(String)}. Every robot drives the same square at the same time: each verb is
 * sent to all robots with its {@code ...Async} form and the group waits for all before the next.
 *
 * <p>Run it: {@code java ... io.robomw.examples.GroupControl tcp://127.0.0.1:7000/nxt-1 tcp://127.0.0.1:7001/ft-1 [SIDE]}.
 */
public final class GroupControl {

    private GroupControl() {
    }

    /**
     * Drives a square with every robot at once.
     *
     * @param robots the robots
     * @param side   side of the square, metres
     * @param speed  metres per second
     * @return each robot's odometry at the end, in the order given
     */
    public static List<Pose> square(List<Robot> robots, double side, double speed) {
        for (int i = 0; i < 4; i++) {
            all(robots.stream().map(r -> r.moveAsync(side, speed)).toList());
            all(robots.stream().map(r -> r.turnAsync(Math.PI / 2, 1.0)).toList());
        }
        return robots.stream().map(Robot::pose).toList();
    }

    private static void all(List<CompletableFuture<Void>> steps) {
        CompletableFuture.allOf(steps.toArray(CompletableFuture[]::new)).join();
    }

    /**
     * @param args remote robot addresses, and optionally the side in metres (default 0.3)
     */
    public static void main(String[] args) {
        List<String> addresses = new ArrayList<>();
        double side = 0.3;
        for (String a : args) {
            if (a.contains("://")) {
                addresses.add(a);
            } else {
                side = Double.parseDouble(a);
            }
        }
        if (addresses.isEmpty()) {
            System.err.println("usage: GroupControl ADDRESS... [SIDE_METRES], e.g. tcp://127.0.0.1:7000/nxt-1 tcp://127.0.0.1:7001/ft-1");
            System.exit(2);
        }
        List<Robot> robots = new ArrayList<>();
        try {
            for (String a : addresses) {
                robots.add(Robots.remote(a));
            }
            List<Pose> poses = square(robots, side, 0.15);
            for (int i = 0; i < robots.size(); i++) {
                Pose p = poses.get(i);
                System.out.printf(Locale.ROOT, "%s: back at (%.3f, %.3f) by odometry, %.3f m from where it started%n",
                        robots.get(i).name(), p.x(), p.y(), Math.hypot(p.x(), p.y()));
            }
        } finally {
            robots.forEach(Robot::close);
        }
    }
}
