package io.robomw.sim.world;

import io.robomw.api.Pose;
import io.robomw.config.description.Body;
import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.yaml.FileScope;
import io.robomw.config.yaml.MappingReader;
import io.robomw.config.yaml.YamlDocument;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

/**
 * Reads and checks a world YAML file; every problem is reported at once with file, line and
 * column, as for robot files. Keys (see {@code docs/simulation.md}):
 *
 * <pre>
 * name: arena
 * arena: { width: 4, height: 3, walls: true, wall_thickness: 0.1, floor: 0.8 }
 * seed: 42
 * physics_hz: 100
 * trajectory: { every: 0.1, max_points: 1000, keep: whole }
 * physics: { engine: dyn4j }    # or swarm
 * obstacles:
 *   - { box: { x: 2, y: 1.5, width: 0.4, height: 0.4, angle: 0 } }
 *   - { circle: { x: 1, y: 2, radius: 0.2 } }
 *   - { polygon: [[3, 0.5], [3.5, 0.5], [3.2, 1.0]] }
 * floor:
 *   - { x: 0.5, y: 0.5, width: 0.3, height: 0.3, brightness: 0.1, color: 1 }
 * robots:
 *   - { robot: ../robots/sim-two-wheeled.yaml, name: r1, x: 0.5, y: 1.5, heading: 0 }
 * swarms:                       # many robots from one entry, named bot-1 ... bot-5000
 *   - { robot: ../robots/swarm-bot.yaml, count: 5000, name: bot, area: { x: 0, y: 0, width: 80, height: 80 }, seed: 7 }
 * water:                        # where boats may go (vehicles, docs/vehicles.md)
 *   - { x: 10, y: 0, width: 20, height: 30 }
 *   - { polygon: [[10, 30], [30, 30], [20, 40]] }
 * wind: { x: 2, y: 0 }          # m/s, the way the air moves
 * current: { x: 0, y: 0.3 }     # m/s, the way the water moves
 * home: { latitude: 50.15, longitude: -5.07, altitude: 0 }   # the origin on Earth
 * </pre>
 *
 * Robot paths are relative to the world file, and must stay in its directory tree
 * ({@link FileScope}): a world from someone else cannot make RoboMW read, and quote, files
 * elsewhere. A robot must start clear of the walls, the obstacles
 * and the other robots (by the body its robot file gives it); one that overlaps something is a
 * problem at its place in the file, naming both (see {@link Placements}); the check runs once the
 * file has no other problem, and skips a robot whose file cannot be read (opening it reports why).
 * A swarm entry's robots are placed by its seed clear of everything before them ({@link SwarmPlacer});
 * an area too small for its count is a problem at the entry, as is a robot file that cannot be read
 * (its body says how much room each robot needs). Stateless.
 */
public final class WorldLoader {

    /** The largest arena side, obstacle, patch or radius, metres; also the farthest coordinate from the origin. */
    public static final double MAX_SIZE = 1000;
    /** The smallest size, metres (1 mm). */
    public static final double MIN_SIZE = 0.001;
    /** The thickest wall, metres. */
    public static final double MAX_WALL = 10;
    /** The most points of one polygon. */
    public static final int MAX_POLYGON_POINTS = 1000;
    /** The most robots of one swarm entry. */
    public static final int MAX_SWARM = 1_000_000;

    private static final String SIZE = "> 0 metres (0.001 to 1000)";
    private static final String COORDINATE = "between -1000 and 1000 metres";
    private static final String ANGLE = "between -2π and 2π radians (-6.2832 to 6.2832)";

    private static boolean size(double v) {
        return v >= MIN_SIZE && v <= MAX_SIZE;
    }

    private static boolean coordinate(double v) {
        return Math.abs(v) <= MAX_SIZE;
    }

    private static boolean angle(double v) {
        return Math.abs(v) <= 2 * Math.PI + 1e-9;
    }

    /**
     * @param file a world YAML file
     * @return its description
     * @throws io.robomw.config.description.DescriptionException listing every problem
     */
    public WorldDescription load(Path file) {
        MappingReader root = YamlDocument.read(file);
        String name = root.text("name").orElse(file.getFileName().toString().replaceFirst("\\.ya?ml$", ""));
        double width = 0;
        double height = 0;
        boolean walls = true;
        double thickness = 0.1;
        double floor = 0.8;
        Optional<MappingReader> arena = root.requireMapping("arena");
        if (arena.isPresent()) {
            MappingReader a = arena.get();
            width = a.requireNumber("width", SIZE, WorldLoader::size);
            height = a.requireNumber("height", SIZE, WorldLoader::size);
            walls = a.bool("walls", true);
            thickness = a.number("wall_thickness", 0.1, "> 0 metres (0.001 to 10)", v -> v >= MIN_SIZE && v <= MAX_WALL);
            floor = a.number("floor", 0.8, "between 0 and 1", v -> v >= 0 && v <= 1);
            a.finish();
        }
        long seed = root.integer("seed", 1);
        double physicsHz = root.number("physics_hz", 100, "between 1 and 10000", v -> v >= 1 && v <= 10_000);
        WorldDescription.TrajectorySettings trajectories = WorldDescription.TrajectorySettings.DEFAULT;
        Optional<MappingReader> trajectory = root.mapping("trajectory");
        if (trajectory.isPresent()) {
            MappingReader t = trajectory.get();
            WorldDescription.TrajectorySettings d = WorldDescription.TrajectorySettings.DEFAULT;
            double every = t.number("every", d.everySeconds(), "> 0 and at most 3600 seconds", v -> v > 0 && v <= 3600);
            int maxPoints = t.integer("max_points", d.maxPoints(), 0, WorldDescription.TrajectorySettings.MAX_POINTS);
            WorldDescription.Keep keep = t.enumValue("keep", WorldDescription.Keep.class, d.keep());
            t.finish();
            // An invalid value is a problem reported below, and reads as its default here.
            trajectories = new WorldDescription.TrajectorySettings(every, maxPoints, keep);
        }
        WorldDescription.PhysicsEngine engine = WorldDescription.PhysicsEngine.DYN4J;
        Optional<MappingReader> physics = root.mapping("physics");
        if (physics.isPresent()) {
            MappingReader p = physics.get();
            engine = p.enumValue("engine", WorldDescription.PhysicsEngine.class, WorldDescription.PhysicsEngine.DYN4J);
            p.finish();
        }
        List<WorldDescription.Obstacle> obstacles = new ArrayList<>();
        Placements placements = new Placements();
        List<Runnable> placing = new ArrayList<>(); // once every value is known to be valid
        for (MappingReader o : root.mappingList("obstacles")) {
            Optional<WorldDescription.Obstacle> obstacle = obstacle(o);
            obstacle.ifPresent(obstacles::add);
            obstacle.ifPresent(ob -> placing.add(() -> place(placements, ob, o)));
        }
        List<WorldDescription.FloorPatch> patches = new ArrayList<>();
        for (MappingReader p : root.mappingList("floor")) {
            patches.add(new WorldDescription.FloorPatch(
                    p.requireNumber("x", COORDINATE, WorldLoader::coordinate), p.requireNumber("y", COORDINATE, WorldLoader::coordinate),
                    p.requireNumber("width", SIZE, WorldLoader::size), p.requireNumber("height", SIZE, WorldLoader::size),
                    p.number("brightness", 0.1, "between 0 and 1", v -> v >= 0 && v <= 1), p.integer("color", 0, 0, 255)));
            p.finish();
        }
        List<WorldDescription.RobotPlacement> robots = new ArrayList<>();
        Set<String> names = new HashSet<>();
        Map<Path, Optional<Body>> bodies = new HashMap<>();
        Path dir = file.toAbsolutePath().getParent();
        FileScope scope = FileScope.of(file);
        for (MappingReader r : root.mappingList("robots")) {
            String robotFile = r.requireText("robot");
            Path robotPath = dir.resolve(robotFile).normalize();
            Optional<String> outside = robotFile.isEmpty() ? Optional.empty() : scope.refusal(robotPath);
            if (outside.isPresent()) {
                r.problem("robot", "refused: " + outside.get());
            } else if (!robotFile.isEmpty() && !Files.isRegularFile(robotPath)) {
                r.problem("robot", "no such robot file: " + robotPath);
            }
            String robotName = r.text("name").orElse(robotPath.getFileName().toString().replaceFirst("\\.ya?ml$", ""));
            if (!names.add(robotName)) {
                r.problem("name", "two robots are named '" + robotName + "'; give each a unique name");
            }
            double x = r.requireNumber("x", COORDINATE, WorldLoader::coordinate);
            double y = r.requireNumber("y", COORDINATE, WorldLoader::coordinate);
            double heading = r.number("heading", 0, ANGLE, WorldLoader::angle);
            if (width > 0 && height > 0 && (x < 0 || y < 0 || x > width || y > height)) {
                r.problem("x", "the robot starts outside the " + width + " × " + height + " m arena, at (" + x + ", " + y + ")");
            }
            r.finish();
            if (Double.isFinite(x) && Double.isFinite(y)) {
                robots.add(new WorldDescription.RobotPlacement(robotPath, robotName, new Pose(x, y, heading)));
                // a refused path is never read, not even for its robot's body
                Optional<Body> body = outside.isPresent() ? Optional.empty() : bodies.computeIfAbsent(robotPath, WorldLoader::body);
                body.ifPresent(b -> placing.add(() -> placements.robot("robot '" + robotName + "'", r.path(), r.mark(), b.length(), b.width(),
                        x, y, heading)));
            }
        }
        List<SwarmEntry> swarmEntries = new ArrayList<>();
        int entry = 0;
        for (MappingReader s : root.mappingList("swarms")) {
            swarmEntry(s, dir, scope, width, height, seed, entry++, bodies).ifPresent(swarmEntries::add);
        }
        WorldDescription.Surroundings surroundings = surroundings(root);
        root.finish();
        List<WorldDescription.Swarm> swarms = new ArrayList<>();
        if (root.problems().isEmpty()) {
            SwarmPlacer placer = new SwarmPlacer();
            for (WorldDescription.Obstacle o : obstacles) {
                double[] b = bounds(o);
                placer.block(b[0], b[1], b[2], b[3]);
            }
            for (WorldDescription.RobotPlacement r : robots) {
                bodies.getOrDefault(r.description(), Optional.empty()).ifPresent(b -> placer.blockRobot(r.start().x(), r.start().y(), b.length(), b.width()));
            }
            for (SwarmEntry s : swarmEntries) {
                place(s, placer, names, robots, swarms, placements, placing);
            }
        }
        if (root.problems().isEmpty()) {
            placing.forEach(Runnable::run);
            if (walls) {
                walls(placements, root.mark("arena"), width, height, thickness);
            }
            placements.check(root.problems());
        }
        root.problems().throwIfAny();
        return new WorldDescription(name, width, height, walls, thickness, floor, obstacles, patches, robots, seed, physicsHz, trajectories,
                engine, file.toString(), surroundings, swarms);
    }

    /** A swarm entry as read, before its robots are placed. */
    private record SwarmEntry(MappingReader entry, Path robot, String name, int count, double x, double y, double width, double height,
                              long seed, double heading, Body body) {
    }

    /** Reads a swarm entry; empty if a value is invalid (reported). */
    private static Optional<SwarmEntry> swarmEntry(MappingReader s, Path dir, FileScope scope, double arenaW, double arenaH, long worldSeed, int index,
                                                   Map<Path, Optional<Body>> bodies) {
        int problemsBefore = s.problems().count();
        String robotFile = s.requireText("robot");
        Path robotPath = dir.resolve(robotFile).normalize();
        Optional<Body> body = Optional.empty();
        // the same rule as a robot's entry: a swarm's robot file stays in the world file's tree, and a refused one is never read
        Optional<String> outside = robotFile.isEmpty() ? Optional.empty() : scope.refusal(robotPath);
        if (outside.isPresent()) {
            s.problem("robot", "refused: " + outside.get());
        } else if (!robotFile.isEmpty() && !Files.isRegularFile(robotPath)) {
            s.problem("robot", "no such robot file: " + robotPath);
        } else if (!robotFile.isEmpty()) {
            body = bodies.computeIfAbsent(robotPath, WorldLoader::body);
            if (body.isEmpty()) {
                s.problem("robot", "cannot place the swarm: robot file " + robotPath + " has problems (mw describe " + robotPath
                        + " lists them), and its body says how much room each robot needs");
            }
        }
        int count = s.integer("count", 0, 1, MAX_SWARM);
        if (!s.has("count")) {
            s.problems().add(s.mark(), "missing key '" + s.path() + ".count': expected an integer from 1 to " + MAX_SWARM + " (how many robots)");
        }
        String stem = s.text("name").orElse(robotPath.getFileName().toString().replaceFirst("\\.ya?ml$", ""));
        if (stem.isBlank()) {
            s.problem("name", "a swarm's name must not be blank: its robots are named after it (name-1, name-2, ...)");
        }
        double x = 0;
        double y = 0;
        double w = arenaW;
        double h = arenaH;
        Optional<MappingReader> area = s.mapping("area");
        if (area.isPresent()) {
            MappingReader a = area.get();
            x = a.requireNumber("x", COORDINATE, WorldLoader::coordinate);
            y = a.requireNumber("y", COORDINATE, WorldLoader::coordinate);
            w = a.requireNumber("width", SIZE, WorldLoader::size);
            h = a.requireNumber("height", SIZE, WorldLoader::size);
            a.finish();
            if (arenaW > 0 && arenaH > 0 && (x < 0 || y < 0 || x + w > arenaW + 1e-9 || y + h > arenaH + 1e-9)) {
                s.problem("area", String.format(java.util.Locale.ROOT, "the area (%s × %s m at (%s, %s)) must lie inside the %s × %s m arena",
                        w(w), w(h), w(x), w(y), w(arenaW), w(arenaH)));
            }
        }
        long seed = s.has("seed") ? s.integer("seed", 0) : worldSeed * 0x9E3779B97F4A7C15L + index;
        double heading = s.has("heading") ? s.number("heading", 0, ANGLE, WorldLoader::angle) : Double.NaN;
        s.finish();
        if (s.problems().count() > problemsBefore || body.isEmpty()) {
            return Optional.empty();
        }
        return Optional.of(new SwarmEntry(s, robotPath, stem, count, x, y, w, h, seed, heading, body.get()));
    }

    /** Places a swarm's robots (or reports that its area is too small), and names them. */
    private static void place(SwarmEntry s, SwarmPlacer placer, Set<String> names, List<WorldDescription.RobotPlacement> robots,
                              List<WorldDescription.Swarm> swarms, Placements placements, List<Runnable> placing) {
        Body b = s.body();
        SwarmPlacer.Placement p = placer.place(s.count(), s.x(), s.y(), s.width(), s.height(), b.length(), b.width(), s.seed(), s.heading());
        if (!p.placed()) {
            s.entry().problems().add(s.entry().mark(), String.format(java.util.Locale.ROOT,
                    "'%s': %d robots do not fit in the %s × %s m area at (%s, %s): each robot of %s (%s × %s m) needs a square of %.3f m "
                            + "(its diagonal and %.0f mm), and %s of them are clear of the obstacles and robots placed before; make the area "
                            + "larger or the count smaller",
                    s.entry().path(), s.count(), w(s.width()), w(s.height()), w(s.x()), w(s.y()), s.robot().getFileName(), w(b.length()),
                    w(b.width()), p.cell(), SwarmPlacer.GAP_METRES * 1000, p.fitting() == 0 ? "none" : "only " + p.fitting()));
            return;
        }
        int first = robots.size();
        for (int k = 0; k < s.count(); k++) {
            String robotName = s.name() + "-" + (k + 1);
            if (!names.add(robotName)) {
                s.entry().problem("name", "swarm '" + s.name() + "' names its robots " + s.name() + "-1 to " + s.name() + "-" + s.count()
                        + ", but another robot is named '" + robotName + "' already; give the swarm another name");
                return;
            }
            double x = p.x()[k];
            double y = p.y()[k];
            double heading = p.heading()[k];
            robots.add(new WorldDescription.RobotPlacement(s.robot(), robotName, new Pose(x, y, heading)));
            placing.add(() -> placements.robot("robot '" + robotName + "'", s.entry().path(), s.entry().mark(), b.length(), b.width(),
                    x, y, heading));
        }
        swarms.add(new WorldDescription.Swarm(s.robot(), s.name(), s.count(), s.x(), s.y(), s.width(), s.height(), s.seed(), first));
    }

    /** @return an obstacle's bounding box {x0, y0, x1, y1} */
    private static double[] bounds(WorldDescription.Obstacle o) {
        if (o instanceof WorldDescription.Circle c) {
            return new double[] {c.x() - c.radius(), c.y() - c.radius(), c.x() + c.radius(), c.y() + c.radius()};
        }
        List<double[]> points;
        if (o instanceof WorldDescription.Box b) {
            double c = Math.cos(b.angle());
            double s = Math.sin(b.angle());
            points = new ArrayList<>();
            for (double[] l : new double[][] {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}}) {
                double lx = l[0] * b.width() / 2;
                double ly = l[1] * b.height() / 2;
                points.add(new double[] {b.x() + lx * c - ly * s, b.y() + lx * s + ly * c});
            }
        } else {
            points = ((WorldDescription.Polygon) o).points();
        }
        double[] r = {Double.POSITIVE_INFINITY, Double.POSITIVE_INFINITY, Double.NEGATIVE_INFINITY, Double.NEGATIVE_INFINITY};
        for (double[] q : points) {
            r[0] = Math.min(r[0], q[0]);
            r[1] = Math.min(r[1], q[1]);
            r[2] = Math.max(r[2], q[0]);
            r[3] = Math.max(r[3], q[1]);
        }
        return r;
    }

    /** The keys vehicles need: water areas, wind, current, home. */
    private WorldDescription.Surroundings surroundings(MappingReader root) {
        List<WorldDescription.WaterArea> water = new ArrayList<>();
        for (MappingReader w : root.mappingList("water")) {
            if (w.has("polygon")) {
                List<double[]> points = new ArrayList<>();
                for (MappingReader.NumberRow row : w.numberRows("polygon")) {
                    if (row.values().length != 2 || !coordinate(row.values()[0]) || !coordinate(row.values()[1])) {
                        w.problems().add(row.mark(), "'" + w.path() + ".polygon' points must be [x, y] pairs " + COORDINATE);
                    } else {
                        points.add(row.values());
                    }
                }
                if (points.size() < 3 || points.size() > MAX_POLYGON_POINTS) {
                    w.problem("polygon", "needs 3 to " + MAX_POLYGON_POINTS + " points, got " + points.size());
                } else if (Math.abs(area(points)) < MIN_SIZE * MIN_SIZE) {
                    w.problem("polygon", "encloses no area; give it some");
                } else {
                    water.add(new WorldDescription.WaterArea(points));
                }
            } else {
                double x = w.requireNumber("x", COORDINATE, WorldLoader::coordinate);
                double y = w.requireNumber("y", COORDINATE, WorldLoader::coordinate);
                double wd = w.requireNumber("width", SIZE, WorldLoader::size);
                double h = w.requireNumber("height", SIZE, WorldLoader::size);
                if (Double.isFinite(x) && Double.isFinite(y) && Double.isFinite(wd) && Double.isFinite(h)) {
                    water.add(WorldDescription.WaterArea.rectangle(x, y, wd, h));
                }
            }
            w.finish();
        }
        double[] wind = flow(root, "wind");
        double[] current = flow(root, "current");
        WorldDescription.GeoOrigin home = WorldDescription.GeoOrigin.SITL_DEFAULT;
        Optional<MappingReader> h = root.mapping("home");
        if (h.isPresent()) {
            MappingReader m = h.get();
            double lat = m.requireNumber("latitude", "between -90 and 90 degrees", v -> Math.abs(v) <= 90);
            double lon = m.requireNumber("longitude", "between -180 and 180 degrees", v -> Math.abs(v) <= 180);
            double alt = m.number("altitude", 0, "between -500 and 10000 metres", v -> v >= -500 && v <= 10_000);
            m.finish();
            if (Math.abs(lat) <= 90 && Math.abs(lon) <= 180 && Double.isFinite(alt)) {
                home = new WorldDescription.GeoOrigin(lat, lon, alt);
            }
        }
        return new WorldDescription.Surroundings(water, wind[0], wind[1], current[0], current[1], home);
    }

    /** A velocity of the air or the water, {@code { x: 2, y: 0 }} in m/s. */
    private static double[] flow(MappingReader root, String key) {
        Optional<MappingReader> f = root.mapping(key);
        if (f.isEmpty()) {
            return new double[]{0, 0};
        }
        MappingReader m = f.get();
        String rule = "between -50 and 50 metres per second";
        double x = m.number("x", 0, rule, v -> Math.abs(v) <= 50);
        double y = m.number("y", 0, rule, v -> Math.abs(v) <= 50);
        m.finish();
        return new double[]{Double.isFinite(x) ? x : 0, Double.isFinite(y) ? y : 0};
    }

    /** @return the body a robot file gives its robot, or empty if the file cannot be read (opening it says why) */
    private static Optional<Body> body(Path robotFile) {
        try {
            return Optional.of(new RobotDescriptionLoader().load(robotFile).body());
        } catch (DescriptionException e) {
            return Optional.empty();
        }
    }

    /** The arena's walls, as the simulated world builds them: boxes of the wall's thickness just outside the arena. */
    private static void walls(Placements placements, org.yaml.snakeyaml.error.Mark arena, double w, double h, double t) {
        placements.box("the arena's bottom wall (y < 0)", "arena", arena, w / 2, -t / 2, w + 2 * t, t, 0);
        placements.box("the arena's top wall (y > " + w(h) + ")", "arena", arena, w / 2, h + t / 2, w + 2 * t, t, 0);
        placements.box("the arena's left wall (x < 0)", "arena", arena, -t / 2, h / 2, t, h, 0);
        placements.box("the arena's right wall (x > " + w(w) + ")", "arena", arena, w + t / 2, h / 2, t, h, 0);
    }

    /** @return a length as a message writes it, without needless decimals */
    private static String w(double metres) {
        return java.math.BigDecimal.valueOf(metres).stripTrailingZeros().toPlainString();
    }

    private static void place(Placements placements, WorldDescription.Obstacle obstacle, MappingReader o) {
        String path = o.path();
        if (obstacle instanceof WorldDescription.Box b) {
            placements.box(String.format(java.util.Locale.ROOT, "the box at (%s, %s)", w(b.x()), w(b.y())), path, o.mark(),
                    b.x(), b.y(), b.width(), b.height(), b.angle());
        } else if (obstacle instanceof WorldDescription.Circle c) {
            placements.circle(String.format(java.util.Locale.ROOT, "the circle at (%s, %s)", w(c.x()), w(c.y())), path, o.mark(), c.x(), c.y(), c.radius());
        } else if (obstacle instanceof WorldDescription.Polygon p) {
            placements.polygon("the polygon", path, o.mark(), p.points());
        }
    }

    private Optional<WorldDescription.Obstacle> obstacle(MappingReader o) {
        Optional<WorldDescription.Obstacle> result = Optional.empty();
        int kinds = 0;
        if (o.has("box")) {
            kinds++;
            result = o.mapping("box").map(b -> {
                WorldDescription.Box box = new WorldDescription.Box(b.requireNumber("x", COORDINATE, WorldLoader::coordinate),
                        b.requireNumber("y", COORDINATE, WorldLoader::coordinate), b.requireNumber("width", SIZE, WorldLoader::size),
                        b.requireNumber("height", SIZE, WorldLoader::size), b.number("angle", 0, ANGLE, WorldLoader::angle));
                b.finish();
                return box;
            });
        }
        if (o.has("circle")) {
            kinds++;
            result = o.mapping("circle").map(c -> {
                WorldDescription.Circle circle = new WorldDescription.Circle(c.requireNumber("x", COORDINATE, WorldLoader::coordinate),
                        c.requireNumber("y", COORDINATE, WorldLoader::coordinate), c.requireNumber("radius", SIZE, WorldLoader::size));
                c.finish();
                return circle;
            });
        }
        if (o.has("polygon")) {
            kinds++;
            List<double[]> points = new ArrayList<>();
            int problemsBefore = o.problems().count();
            List<MappingReader.NumberRow> rows = o.numberRows("polygon");
            boolean valid = o.problems().count() == problemsBefore;
            for (MappingReader.NumberRow row : rows) {
                if (row.values().length != 2) {
                    o.problems().add(row.mark(), "'" + o.path() + ".polygon' points must be [x, y] pairs");
                    valid = false;
                } else if (!coordinate(row.values()[0]) || !coordinate(row.values()[1])) {
                    o.problems().add(row.mark(), "'" + o.path() + ".polygon' points must have coordinates " + COORDINATE + ", got ["
                            + row.values()[0] + ", " + row.values()[1] + "]");
                    valid = false;
                } else {
                    points.add(row.values());
                }
            }
            if (!valid) {
                // the points' own problems are reported
            } else if (points.size() > MAX_POLYGON_POINTS) {
                o.problem("polygon", "has " + points.size() + " points; at most " + MAX_POLYGON_POINTS + " are allowed");
            } else if (points.size() < 3) {
                o.problem("polygon", "needs at least 3 points, got " + points.size());
            } else if (shortestEdge(points) < MIN_SIZE) {
                o.problem("polygon", "has two neighbouring points closer than 1 mm; give points at least 0.001 m apart");
            } else if (!convexCounterClockwise(points)) {
                o.problem("polygon", "must be convex with its points anti-clockwise");
            } else if (area(points) < MIN_SIZE * MIN_SIZE) {
                o.problem("polygon", "encloses less than 1 mm² (its points lie almost on a line); give it some area");
            } else {
                result = Optional.of(new WorldDescription.Polygon(points));
            }
        }
        if (kinds != 1) {
            o.problems().add(o.mark(), "'" + o.path() + "' must be exactly one of box, circle, polygon");
        }
        o.finish();
        return kinds == 1 ? result : Optional.empty();
    }

    private static double shortestEdge(List<double[]> p) {
        double shortest = Double.POSITIVE_INFINITY;
        for (int i = 0; i < p.size(); i++) {
            double[] a = p.get(i);
            double[] b = p.get((i + 1) % p.size());
            shortest = Math.min(shortest, Math.hypot(b[0] - a[0], b[1] - a[1]));
        }
        return shortest;
    }

    /** Shoelace formula: the area of a simple polygon, positive when anti-clockwise. */
    private static double area(List<double[]> p) {
        double twice = 0;
        for (int i = 0; i < p.size(); i++) {
            double[] a = p.get(i);
            double[] b = p.get((i + 1) % p.size());
            twice += a[0] * b[1] - b[0] * a[1];
        }
        return twice / 2;
    }

    private static boolean convexCounterClockwise(List<double[]> p) {
        int n = p.size();
        for (int i = 0; i < n; i++) {
            double[] a = p.get(i);
            double[] b = p.get((i + 1) % n);
            double[] c = p.get((i + 2) % n);
            double cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
            if (cross <= 0) {
                return false;
            }
        }
        return true;
    }
}
