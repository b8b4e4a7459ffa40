package io.robomw.console.foxglove;

import com.fasterxml.jackson.databind.JsonNode;

import java.io.IOException;
import java.util.Set;

/**
 * A velocity a client published to drive a robot: a JSON {@code geometry_msgs/Twist}
 * ({@code {"linear":{"x":0.2,"y":0,"z":0},"angular":{"x":0,"y":0,"z":0.5}}}), which is what
 * Foxglove's Teleop panel publishes over a JSON connection. RoboMW's ground robots drive forwards
 * ({@code linear.x}, m/s) and turn ({@code angular.z}, rad/s, left positive); the other four
 * components must be 0 or left out, and every number finite.
 *
 * @param linear  m/s
 * @param angular rad/s
 */
public record Twist(double linear, double angular) {

    /** The schema names a client may advertise a Twist channel with (ROS 1 and ROS 2 spellings). */
    public static final Set<String> SCHEMA_NAMES = Set.of("geometry_msgs/Twist", "geometry_msgs/msg/Twist");

    /** Standing still. */
    public static final Twist STOP = new Twist(0, 0);

    /**
     * @param json a message's payload
     * @return the Twist it is
     * @throws IOException saying what is wrong with it
     */
    public static Twist parse(byte[] json) throws IOException {
        JsonNode n;
        try {
            n = Json.MAPPER.readTree(json);
        } catch (IOException e) {
            throw new IOException("a Twist must be JSON, " + e.getMessage().lines().findFirst().orElse(""));
        }
        if (n == null || !n.isObject()) {
            throw new IOException("a Twist is a JSON object {\"linear\":{x,y,z},\"angular\":{x,y,z}}");
        }
        JsonNode linear = vector(n, "linear");
        JsonNode angular = vector(n, "angular");
        requireZero(linear, "linear", "y");
        requireZero(linear, "linear", "z");
        requireZero(angular, "angular", "x");
        requireZero(angular, "angular", "y");
        return new Twist(number(linear, "linear", "x"), number(angular, "angular", "z"));
    }

    private static JsonNode vector(JsonNode n, String field) throws IOException {
        JsonNode v = n.get(field);
        if (v == null || !v.isObject()) {
            throw new IOException("a Twist needs an object \"" + field + "\" {x,y,z}, got " + (v == null ? "none" : Json.shortly(v.toString())));
        }
        return v;
    }

    private static double number(JsonNode v, String vector, String axis) throws IOException {
        JsonNode x = v.get(axis);
        if (x == null || x.isNull()) {
            return 0;
        }
        if (!x.isNumber() || !Double.isFinite(x.asDouble())) {
            throw new IOException("Twist " + vector + "." + axis + " must be a finite number, got " + Json.shortly(x.toString()));
        }
        return x.asDouble();
    }

    private static void requireZero(JsonNode v, String vector, String axis) throws IOException {
        double x = number(v, vector, axis);
        if (x != 0) {
            throw new IOException("Twist " + vector + "." + axis + " = " + x + " cannot be driven: a RoboMW robot drives forwards (linear.x) and turns (angular.z); "
                    + "the other components must be 0");
        }
    }
}
