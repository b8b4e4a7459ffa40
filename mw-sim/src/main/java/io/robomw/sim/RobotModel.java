package io.robomw.sim;

import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.config.kinematics.DifferentialKinematics;

import java.util.ArrayList;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * What the simulator derives from a robot file once for every robot of a world read from it: the
 * drive's kinematics, the motor ports, the sensors' models. A swarm of 100,000 robots from one
 * file then holds one of each instead of 100,000 (a robot's sensor models alone took about 1.3 KB
 * of heap a robot, and a step read eight of them per robot from memory). Immutable.
 */
final class RobotModel {

    final DifferentialKinematics kinematics;
    /** The motor ports, in the description's order. */
    final String[] ports;
    final int leftIndex;
    final int rightIndex;
    final int[] actuatorIndex;
    /** Every sensor's model, in the description's order. */
    final List<SensorModel> sensors;
    final Map<String, SensorModel> byName;
    /** The range sensors, in the description's order ({@link SensorModel#rangeIndex()} is the place here). */
    final List<SensorModel> rangeSensors;
    /** Whether a range sensor is noisy (each robot then has a generator per sensor). */
    final boolean noisy;
    /**
     * The radius about a robot's centre that holds every point of its range sensors' rays, if the circle's box is about
     * as tight as the rays' own box (sensors all round the robot: at most twice its area in the robot's frame, which a
     * box of the rays can reach by turning), for sensing to gather what is around the robot without finding the rays'
     * box at every sample ({@link io.robomw.sim.sensing.RangeIndex#castRaysWithin}); 0 otherwise.
     */
    final double rangeReach;
    final boolean hasTouch;
    final boolean hasAccel;

    /**
     * @param description a robot file's description (any of the renamed copies a world makes of it)
     * @param physicsHz   the world's step rate
     */
    RobotModel(RobotDescription description, double physicsHz) {
        this.kinematics = description.drive().map(DifferentialKinematics::new).orElse(null);
        this.ports = description.motorPorts().toArray(String[]::new);
        this.leftIndex = description.drive().map(d -> portIndex(d.left().port())).orElse(-1);
        this.rightIndex = description.drive().map(d -> portIndex(d.right().port())).orElse(-1);
        this.actuatorIndex = description.actuators().stream().mapToInt(a -> portIndex(a.port())).toArray();
        List<SensorModel> all = new ArrayList<>();
        List<SensorModel> range = new ArrayList<>();
        Map<String, SensorModel> names = new LinkedHashMap<>();
        boolean touch = false;
        boolean acc = false;
        boolean noise = false;
        for (SensorSpec s : description.sensors()) {
            boolean ranging = SensorModel.kindOf(s.type()) == SensorModel.Kind.RANGE;
            SensorModel m = new SensorModel(s, description.body(), ranging ? range.size() : -1, physicsHz);
            all.add(m);
            names.put(s.name(), m);
            if (ranging) {
                range.add(m);
                noise |= m.noisy();
            }
            touch |= m.kind() == SensorModel.Kind.CONTACT;
            acc |= m.kind() == SensorModel.Kind.ACCELERATION;
        }
        this.sensors = List.copyOf(all);
        this.byName = Collections.unmodifiableMap(names);
        this.rangeSensors = List.copyOf(range);
        this.noisy = noise;
        this.rangeReach = rangeReach(range);
        this.hasTouch = touch;
        this.hasAccel = acc;
    }

    /** @return a motor port's index, or -1 */
    int portIndex(String port) {
        for (int i = 0; i < ports.length; i++) {
            if (ports[i].equals(port)) {
                return i;
            }
        }
        return -1;
    }

    /**
     * What makes two descriptions give the same model: the very objects a world's renamed copies of
     * one robot file share (its drive, body, sensors, actuators, legs).
     */
    record Key(Object drive, Object body, Object sensors, Object actuators, Object legs) {
        static Key of(RobotDescription d) {
            return new Key(d.drive(), d.body(), d.sensors(), d.actuators(), d.leggedDrive());
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Key k && k.drive == drive && k.body == body && k.sensors == sensors && k.actuators == actuators && k.legs == legs;
        }

        @Override
        public int hashCode() {
            return System.identityHashCode(drive) * 31 + System.identityHashCode(sensors) * 17 + System.identityHashCode(body);
        }
    }

    /** @return {@link #rangeReach} of these range sensors */
    private static double rangeReach(List<SensorModel> range) {
        double radius = 0;
        double[] box = {Double.POSITIVE_INFINITY, Double.POSITIVE_INFINITY, Double.NEGATIVE_INFINITY, Double.NEGATIVE_INFINITY};
        for (SensorModel m : range) {
            if (!m.stretch(box)) {
                return 0;
            }
            radius = Math.max(radius, m.reach());
        }
        double area = (box[2] - box[0]) * (box[3] - box[1]);
        return !range.isEmpty() && 4 * radius * radius <= 2 * area ? radius : 0;
    }
}
