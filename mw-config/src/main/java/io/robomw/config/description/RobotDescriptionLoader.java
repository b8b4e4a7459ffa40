package io.robomw.config.description;

import io.robomw.api.Capability;
import io.robomw.api.Position;
import io.robomw.api.SensorType;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.config.yaml.MappingReader;
import io.robomw.config.yaml.Range;
import io.robomw.config.yaml.YamlDocument;

import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.OptionalDouble;
import java.util.Set;

/**
 * Reads a robot description from YAML and checks it completely: every problem (unknown key, wrong
 * type, missing port, two sensors on one port, a port used twice...) is reported with file, line
 * and column, all at once. A description that has any problem is never returned, so nothing is
 * started from a bad file. The keys are documented in {@code docs/robot-yaml.md}.
 *
 * <p>Stateless and thread-safe.
 */
public final class RobotDescriptionLoader {

    /** The default execution action thread rate. */
    public static final double DEFAULT_CYCLE_HZ = 100;
    /** The default watchdog timeout of continuous commands, seconds. */
    public static final double DEFAULT_WATCHDOG_SECONDS = 0.5;

    // Each rule once: its range makes both the check and the words of the problem.
    private static final Range CYCLE_HZ = Range.between(1, 1000, "");
    private static final Range WATCHDOG = Range.between(0, 3600, "seconds").noting("0 turns it off");
    private static final Range WHEEL_DIAMETER = Range.positive(0.001, 10, "metres");
    private static final Range TRACK_WIDTH = Range.positive(0.001, 100, "metres");
    private static final Range GEAR_RATIO = Range.positive(0.001, 10_000, "");
    private static final Range SPEED = Range.above(0, 100, "metres per second");
    private static final Range TURN_RATE = Range.above(0, 100, "radians per second");
    private static final Range CLIMB_RATE = Range.between(0, 50, "metres per second").noting("> 0 for an air vehicle");
    private static final Range VEHICLE_TURN_RATE = Range.above(0, 20, "radians per second");
    private static final Range ACCEPTANCE_RADIUS = Range.above(0, 1000, "metres");
    private static final Range TAKEOFF_ALTITUDE = Range.between(0, 1000, "metres");
    private static final Range STEP_FREQUENCY = Range.above(0, 100, "steps per second");
    private static final Range JITTER = Range.fromBelow(0, 1, "").noting("a fraction of the speed");
    private static final Range SLIP = Range.fromBelow(0, 1, "").noting("a fraction of the motion");
    private static final Range ACTION_DURATION = Range.above(0, 3600, "seconds");
    private static final Range BODY_SIZE = Range.positive(0.001, 100, "metres");
    private static final Range BODY_MASS = Range.positive(0.001, 100_000, "kilograms");
    private static final Range FRICTION = Range.between(0, 10, "");
    private static final Range LUX_AT_FULL_SCALE = Range.above(0, 1_000_000, "");
    private static final Range ACTION_DEGREES = Range.between(-1_000_000, 1_000_000, "motor degrees").noting("or 'argument'");
    private static final Range ACTION_SPEED = Range.above(0, 100_000, "motor degrees per second");

    /**
     * @param file a robot YAML file
     * @return its description
     * @throws DescriptionException listing every problem
     */
    public RobotDescription load(Path file) {
        return read(YamlDocument.read(file));
    }

    /**
     * @param yaml   YAML text
     * @param source its name in messages
     * @return its description
     * @throws DescriptionException listing every problem
     */
    public RobotDescription parse(String yaml, String source) {
        return read(YamlDocument.parse(yaml, source));
    }

    private RobotDescription read(MappingReader root) {
        String source = root.problems().file();
        String name = root.requireText("name");
        String platform = root.requireText("platform");
        Map<String, Object> connection = root.plainMap("connection");
        double cycleHz = root.number("cycle_hz", DEFAULT_CYCLE_HZ, CYCLE_HZ);
        double watchdog = root.number("watchdog", DEFAULT_WATCHDOG_SECONDS, WATCHDOG);
        Set<Capability> capabilities = new LinkedHashSet<>(root.enumList("capabilities", Capability.class));
        if (!root.has("capabilities")) {
            capabilities.add(Capability.GROUND);
        }
        Optional<MappingReader> driveNode = root.mapping("drive");
        Optional<DifferentialDrive> drive = driveNode.filter(m -> !legged(m) && !vehicle(m)).flatMap(this::drive);
        Optional<LeggedDrive> leggedDrive = driveNode.filter(this::legged).flatMap(this::leggedDrive);
        Optional<VehicleDrive> vehicleDrive = driveNode.filter(this::vehicle).flatMap(this::vehicleDrive);
        if (vehicleDrive.isPresent() && !root.has("capabilities")) {
            capabilities.clear();
            capabilities.add(switch (vehicleDrive.get().medium()) {
                case AIR -> Capability.AIR;
                case WATER -> Capability.WATER;
                case GROUND -> Capability.GROUND;
            });
        }
        Body body = root.mapping("body").map(this::body).orElse(Body.DEFAULT);
        List<Read<SensorSpec>> sensors = root.mappingList("sensors").stream()
                .flatMap(m -> sensor(m).map(s -> new Read<>(s, m)).stream()).toList();
        List<Read<ActuatorSpec>> actuators = root.mappingList("actuators").stream()
                .flatMap(m -> actuator(m).map(a -> new Read<>(a, m)).stream()).toList();
        List<HighLevelAction> highLevelActions = root.mapping("actions").map(this::highLevelActions).orElse(List.of());
        checkPorts(drive, driveNode, sensors, actuators);
        checkActionNames(root, highLevelActions, actuators);
        ComponentSections components = new ComponentSections(name, source);
        MessagingConfig messaging = components.messaging(root.mapping("messaging"));
        AgencyConfig agency = components.agency(root.mapping("agency"));
        root.finish();
        root.problems().throwIfAny();
        return new RobotDescription(name, platform, new ConnectionSettings(connection, source),
                Duration.ofNanos(Math.round(1e9 / cycleHz)), Duration.ofNanos(Math.round(watchdog * 1e9)),
                capabilities, drive, body, sensors.stream().map(Read::value).toList(),
                actuators.stream().map(Read::value).toList(), leggedDrive, highLevelActions, messaging, agency, source, vehicleDrive);
    }

    private Optional<DifferentialDrive> drive(MappingReader m) {
        String type = m.text("type").orElse(DriveKind.DIFFERENTIAL.yamlName());
        if (DriveKind.fromYaml(type).isEmpty()) {
            m.problem("type", "must be " + DriveKind.choices() + ", got '" + type + "'");
        }
        double wheel = m.requireNumber("wheel_diameter", WHEEL_DIAMETER);
        double track = m.requireNumber("track_width", TRACK_WIDTH);
        double gear = m.number("gear_ratio", 1, GEAR_RATIO);
        double max = m.requireNumber("max_speed", SPEED);
        int ticks = m.integer("encoder_ticks_per_revolution", 360, 0, 1_000_000);
        Optional<DifferentialDrive.Wheel> left = m.requireMapping("left").map(this::wheel);
        Optional<DifferentialDrive.Wheel> right = m.requireMapping("right").map(this::wheel);
        if (left.isPresent() && right.isPresent() && left.get().port().equals(right.get().port())) {
            m.problem("right", "port " + right.get().port() + " is already used by the left wheel; each wheel needs its own motor port");
        }
        m.finish();
        if (left.isEmpty() || right.isEmpty() || Double.isNaN(wheel) || Double.isNaN(track) || Double.isNaN(max)) {
            return Optional.empty();
        }
        if (left.get().port().equals(right.get().port())) {
            return Optional.empty();
        }
        return Optional.of(new DifferentialDrive(wheel, track, gear, max, ticks, left.get(), right.get()));
    }

    private boolean legged(MappingReader driveNode) {
        return driveNode.has("type") && driveNode.text("type").flatMap(DriveKind::fromYaml).map(DriveKind.LEGGED::equals).orElse(false);
    }

    private boolean vehicle(MappingReader driveNode) {
        return driveNode.has("type") && driveNode.text("type").flatMap(DriveKind::fromYaml).map(DriveKind.VEHICLE::equals).orElse(false);
    }

    private Optional<VehicleDrive> vehicleDrive(MappingReader m) {
        m.text("type");
        VehicleDrive.Medium medium = m.enumValue("medium", VehicleDrive.Medium.class, null);
        if (!m.has("medium")) {
            m.problem("medium", "missing: say where the vehicle moves: air, water or ground");
        }
        VehicleDrive.Autopilot autopilot = m.enumValue("autopilot", VehicleDrive.Autopilot.class, VehicleDrive.Autopilot.ARDUPILOT);
        double max = m.requireNumber("max_speed", SPEED);
        double climb = m.number("max_climb_rate", medium == VehicleDrive.Medium.AIR ? 1.5 : 0, CLIMB_RATE);
        double turnRate = m.number("max_turn_rate", Math.toRadians(90), VEHICLE_TURN_RATE);
        double acceptance = m.number("acceptance_radius", 0.5, ACCEPTANCE_RADIUS);
        double takeoff = m.number("takeoff_altitude", 2.0, TAKEOFF_ALTITUDE);
        if (medium == VehicleDrive.Medium.AIR && climb == 0) {
            m.problem("max_climb_rate", "an air vehicle must be able to climb: give max_climb_rate > 0");
        }
        if (medium != null && medium != VehicleDrive.Medium.AIR && m.has("max_climb_rate") && climb > 0) {
            m.problem("max_climb_rate", "a " + medium.yamlName() + " vehicle does not climb; leave max_climb_rate out");
        }
        m.finish();
        if (medium == null || Double.isNaN(max) || Double.isNaN(climb) || Double.isNaN(turnRate) || Double.isNaN(acceptance)
                || Double.isNaN(takeoff) || (medium == VehicleDrive.Medium.AIR) != (climb > 0)) {
            return Optional.empty();
        }
        return Optional.of(new VehicleDrive(medium, autopilot, max, climb, turnRate, acceptance, takeoff));
    }

    private Optional<LeggedDrive> leggedDrive(MappingReader m) {
        m.text("type");
        double max = m.requireNumber("max_speed", SPEED);
        double turnRate = m.requireNumber("max_turn_rate", TURN_RATE);
        Optional<MappingReader> commands = m.requireMapping("commands");
        Optional<CommandTemplate> move = commands.flatMap(c -> template(c, "move", LeggedDrive.MOVE_VALUES, true));
        Optional<CommandTemplate> turn = commands.flatMap(c -> template(c, "turn", LeggedDrive.TURN_VALUES, true));
        Optional<CommandTemplate> arc = commands.flatMap(c -> template(c, "arc", LeggedDrive.ARC_VALUES, false));
        Optional<CommandTemplate> drive = commands.flatMap(c -> template(c, "drive", LeggedDrive.DRIVE_VALUES, false));
        Optional<CommandTemplate> stop = commands.flatMap(c -> template(c, "stop", java.util.Set.of(), false));
        commands.ifPresent(MappingReader::finish);
        LeggedDrive.Gait gait = m.mapping("gait").map(this::gait).orElse(LeggedDrive.Gait.DEFAULT);
        m.finish();
        if (move.isEmpty() || turn.isEmpty() || Double.isNaN(max) || Double.isNaN(turnRate)) {
            return Optional.empty();
        }
        return Optional.of(new LeggedDrive(max, turnRate, move.get(), turn.get(), arc, drive, stop, gait));
    }

    /** Reads a command template, reporting a bad placeholder at its key. */
    private Optional<CommandTemplate> template(MappingReader m, String key, java.util.Set<String> allowed, boolean required) {
        String text = required ? m.requireText(key) : m.text(key).orElse("");
        if (text.isEmpty()) {
            if (m.has(key) && !required) {
                m.problem(key, "must not be empty; leave the key out if the firmware has no such command");
            }
            return Optional.empty();
        }
        try {
            return Optional.of(CommandTemplate.parse(text, allowed));
        } catch (IllegalArgumentException e) {
            m.problem(key, e.getMessage());
            return Optional.empty();
        }
    }

    private LeggedDrive.Gait gait(MappingReader m) {
        LeggedDrive.Gait g = new LeggedDrive.Gait(
                m.number("step_frequency", LeggedDrive.Gait.DEFAULT.stepFrequency(), STEP_FREQUENCY),
                m.number("jitter", 0, JITTER),
                m.number("slip", 0, SLIP));
        m.finish();
        return g;
    }

    private List<HighLevelAction> highLevelActions(MappingReader m) {
        List<HighLevelAction> out = new ArrayList<>();
        for (String name : m.keys()) {
            m.mapping(name).ifPresent(a -> highLevelAction(name, a).ifPresent(out::add));
        }
        m.finish();
        return out;
    }

    private Optional<HighLevelAction> highLevelAction(String name, MappingReader a) {
        List<String> arguments = a.textList("arguments");
        Set<String> seen = new HashSet<>();
        boolean ok = true;
        for (String arg : arguments) {
            if (!arg.matches("[a-z][a-z0-9_]*")) {
                a.problem("arguments", "argument names are lower-case words (angle, speed), got '" + arg + "'");
                ok = false;
            } else if (arg.equals("duration")) {
                a.problem("arguments", "'duration' is given to every action's template already; name the argument otherwise");
                ok = false;
            } else if (!seen.add(arg)) {
                a.problem("arguments", "argument '" + arg + "' is listed twice");
                ok = false;
            }
        }
        Set<String> allowed = new HashSet<>(arguments);
        allowed.add("duration");
        Optional<CommandTemplate> command = template(a, "command", allowed, true);
        double duration = a.requireNumber("duration", ACTION_DURATION);
        List<String> uses = a.textList("uses");
        if (uses.isEmpty() && !a.has("uses")) {
            a.problem("uses", "missing: name the actuator groups the action drives, for example [legs] or [head]");
        } else if (uses.isEmpty()) {
            a.problem("uses", "must name at least one actuator group, for example [legs] or [head]");
        }
        a.finish();
        if (command.isEmpty() || Double.isNaN(duration) || uses.isEmpty() || !ok || name.isBlank()) {
            return Optional.empty();
        }
        return Optional.of(new HighLevelAction(name, command.get(), arguments, duration, new LinkedHashSet<>(uses)));
    }

    private void checkActionNames(MappingReader root, List<HighLevelAction> actions, List<Read<ActuatorSpec>> actuators) {
        Set<String> actuatorActions = new HashSet<>();
        for (Read<ActuatorSpec> a : actuators) {
            for (String action : a.value().actions().keySet()) {
                actuatorActions.add(a.value().name() + "." + action);
            }
        }
        for (HighLevelAction a : actions) {
            if (actuatorActions.contains(a.name())) {
                root.problem("actions", "action '" + a.name() + "' is also an action of an actuator; names must be unique");
            }
        }
    }

    private DifferentialDrive.Wheel wheel(MappingReader m) {
        DifferentialDrive.Wheel w = new DifferentialDrive.Wheel(m.requireText("port"), m.bool("reversed", false), m.text("counter"));
        m.finish();
        return w;
    }

    private Body body(MappingReader m) {
        Body b = new Body(
                m.number("length", Body.DEFAULT.length(), BODY_SIZE),
                m.number("width", Body.DEFAULT.width(), BODY_SIZE),
                m.number("mass", Body.DEFAULT.mass(), BODY_MASS),
                m.number("friction", Body.DEFAULT.friction(), FRICTION));
        m.finish();
        return b;
    }

    private Optional<SensorSpec> sensor(MappingReader m) {
        String name = m.requireText("name");
        SensorType type = m.enumValue("type", SensorType.class, null);
        Position position = m.enumValue("position", Position.class, null);
        String port = m.requireText("port");
        Conversion conversion = m.mapping("conversion").map(this::conversion).orElse(Conversion.IDENTITY);
        Map<String, Object> options = m.plainMap("options");
        m.finish();
        if (name.isEmpty() || type == null || position == null || port.isEmpty()) {
            return Optional.empty();
        }
        return Optional.of(new SensorSpec(name, type, position, port, conversion, options));
    }

    private Conversion conversion(MappingReader m) {
        double scale = m.number("scale", 1, Range.ANY);
        double offset = m.number("offset", 0, Range.ANY);
        List<Conversion.Point> table = new ArrayList<>();
        for (MappingReader.NumberRow row : m.numberRows("table")) {
            if (row.values().length != 2) {
                m.problems().add(row.mark(), "'" + m.path() + ".table' rows must be [raw, value] pairs");
            } else if (!table.isEmpty() && row.values()[0] <= table.get(table.size() - 1).raw()) {
                m.problems().add(row.mark(), "'" + m.path() + ".table' raw values must increase, got " + row.values()[0]
                        + " after " + table.get(table.size() - 1).raw());
            } else {
                table.add(new Conversion.Point(row.values()[0], row.values()[1]));
            }
        }
        if (m.has("table") && (m.has("scale") || m.has("offset"))) {
            m.problem("table", "give either a table or scale/offset, not both");
        }
        OptionalDouble threshold = m.optionalNumber("threshold", Range.ANY);
        boolean below = m.bool("true_below", false);
        OptionalDouble lux = m.optionalNumber("lux_at_full_scale", LUX_AT_FULL_SCALE);
        m.finish();
        return new Conversion(scale, offset, table, threshold, below, lux);
    }

    private Optional<ActuatorSpec> actuator(MappingReader m) {
        String name = m.requireText("name");
        String port = m.requireText("port");
        Map<String, ActuatorSpec.Action> actions = new LinkedHashMap<>();
        m.requireMapping("actions").ifPresent(a -> {
            for (String actionName : a.keys()) {
                a.mapping(actionName).ifPresent(spec -> {
                    OptionalDouble degrees = OptionalDouble.empty();
                    if (!spec.text("degrees").map("argument"::equals).orElse(false)) {
                        degrees = spec.optionalNumber("degrees", ACTION_DEGREES);
                        if (degrees.isEmpty() && !spec.has("degrees")) {
                            spec.problem("degrees", "missing: give motor degrees, or 'argument' to take the angle when performed");
                        }
                    }
                    double speed = spec.requireNumber("speed", ACTION_SPEED);
                    spec.finish();
                    actions.put(actionName, new ActuatorSpec.Action(degrees, speed));
                });
            }
            a.finish();
        });
        m.finish();
        if (name.isEmpty() || port.isEmpty()) {
            return Optional.empty();
        }
        if (name.contains(".")) {
            m.problem("name", "must not contain '.', which separates actuator and action in perform(\"name.action\")");
        }
        return Optional.of(new ActuatorSpec(name, port, actions));
    }

    private void checkPorts(Optional<DifferentialDrive> drive, Optional<MappingReader> driveNode, List<Read<SensorSpec>> sensors,
                            List<Read<ActuatorSpec>> actuators) {
        Map<String, String> motorUse = new LinkedHashMap<>();
        drive.ifPresent(d -> {
            motorUse.put(d.left().port(), "the left wheel");
            motorUse.put(d.right().port(), "the right wheel");
        });
        for (Read<ActuatorSpec> a : actuators) {
            String previous = motorUse.putIfAbsent(a.value().port(), "actuator '" + a.value().name() + "'");
            if (previous != null) {
                a.node().problem("port", "motor port " + a.value().port() + " is already used by " + previous);
            }
        }
        Map<String, String> inputUse = new HashMap<>();
        drive.ifPresent(d -> {
            d.left().counter().ifPresent(c -> inputUse.put(c, "the left wheel's counter"));
            d.right().counter().ifPresent(c -> {
                if (inputUse.putIfAbsent(c, "the right wheel's counter") != null) {
                    driveNode.ifPresent(n -> n.problem("right", "counter input " + c + " is already the left wheel's counter; each wheel needs its own"));
                }
            });
        });
        Set<String> actuatorNames = new HashSet<>();
        for (Read<ActuatorSpec> a : actuators) {
            if (!actuatorNames.add(a.value().name())) {
                a.node().problem("name", "two actuators are named '" + a.value().name() + "'; names must be unique");
            }
        }
        Set<String> names = new HashSet<>();
        for (Read<SensorSpec> read : sensors) {
            SensorSpec s = read.value();
            if (!names.add(s.name())) {
                read.node().problem("name", "two sensors are named '" + s.name() + "'; names must be unique");
            }
            if (s.type() == SensorType.TACHO) {
                if (!motorUse.containsKey(s.port())) {
                    read.node().problem("port", "a tacho sensor must be on a motor port the description uses ("
                            + String.join(", ", motorUse.keySet()) + "), got " + s.port());
                }
                continue;
            }
            String previous = inputUse.putIfAbsent(s.port(), "sensor '" + s.name() + "'");
            if (previous != null) {
                read.node().problem("port", "input port " + s.port() + " is already used by " + previous + "; one sensor per port");
            }
        }
    }

    /** A value read from a mapping, with the mapping, for checks across several values. */
    private record Read<T>(T value, MappingReader node) {
    }
}
