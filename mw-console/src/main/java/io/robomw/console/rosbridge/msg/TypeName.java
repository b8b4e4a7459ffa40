package io.robomw.console.rosbridge.msg;

import java.util.Objects;
import java.util.regex.Pattern;

/**
 * The name of a ROS 2 interface: a message ({@code nav_msgs/msg/Odometry}) or a service
 * ({@code robomw_msgs/srv/Move}). Clients write it two ways, and both are accepted, as
 * rosbridge_suite's {@code ros_loader} accepts them: with the interface directory
 * ({@code geometry_msgs/msg/Twist}, ROS 2's spelling) and without ({@code geometry_msgs/Twist},
 * ROS 1's, which roslibpy's own helpers still use).
 *
 * @param pkg  the package, {@code geometry_msgs}
 * @param kind message or service
 * @param name the type's name in the package, {@code Twist}
 */
public record TypeName(String pkg, Kind kind, String name) {

    private static final Pattern PART = Pattern.compile("[A-Za-z][A-Za-z0-9_]*");

    /** What a name names. */
    public enum Kind {
        /** A message: the {@code msg} directory. */
        MSG("msg"),
        /** A service: the {@code srv} directory. */
        SRV("srv");

        private final String directory;

        Kind(String directory) {
            this.directory = directory;
        }

        /** @return the directory its files are in, and the middle part of its full name */
        public String directory() {
            return directory;
        }
    }

    /** Checks each part. */
    public TypeName {
        Objects.requireNonNull(kind, "kind");
        if (pkg == null || !PART.matcher(pkg).matches() || name == null || !PART.matcher(name).matches()) {
            throw new IllegalArgumentException("'" + pkg + "/" + name + "' is not a ROS type name: package and type are letters, digits and '_', "
                    + "starting with a letter");
        }
    }

    /**
     * @param text a name as a client writes it: {@code pkg/Type} or {@code pkg/msg/Type} (or {@code pkg/srv/Type})
     * @param kind what it must name
     * @return the name
     * @throws IllegalArgumentException if it is neither form, or its middle part is not the kind's directory
     */
    public static TypeName parse(String text, Kind kind) {
        if (text == null || text.isBlank()) {
            throw new IllegalArgumentException("no type given: a ROS " + kind.directory + " type is written pkg/" + kind.directory + "/Type or pkg/Type");
        }
        String[] parts = text.split("/", -1);
        if (parts.length == 2) {
            return new TypeName(parts[0], kind, parts[1]);
        }
        if (parts.length == 3 && parts[1].equals(kind.directory)) {
            return new TypeName(parts[0], kind, parts[2]);
        }
        throw new IllegalArgumentException("'" + text + "' is not a ROS " + kind.directory + " type: write pkg/" + kind.directory + "/Type or pkg/Type"
                + (parts.length == 3 ? " (the middle part must be '" + kind.directory + "')" : ""));
    }

    /** @return the ROS 2 spelling, {@code pkg/msg/Type}, as topic and service types are listed */
    public String full() {
        return pkg + "/" + kind.directory + "/" + name;
    }

    /** @return the short spelling, {@code pkg/Type}, as rosapi's type definitions name their types */
    public String shortName() {
        return pkg + "/" + name;
    }

    @Override
    public String toString() {
        return full();
    }
}
