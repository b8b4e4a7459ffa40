package io.robomw.sim.world;

import io.robomw.api.Pose;

import java.nio.file.Path;
import java.util.List;

/**
 * A simulated world, as read from a world YAML file: a walled arena with obstacles and floor
 * patches, and the robots in it. Coordinates in metres with the origin at the arena's lower-left
 * corner; angles in radians, anti-clockwise from the x axis.
 *
 * @param name            the world's name
 * @param width           arena width (x), metres
 * @param height          arena height (y), metres
 * @param walls           whether the arena is closed by walls
 * @param wallThickness   thickness of those walls, metres
 * @param floorBrightness brightness of the bare floor, 0 (black) to 1 (white)
 * @param obstacles       static obstacles
 * @param patches         floor patches seen by light and colour sensors
 * @param robots          the robots and where they start
 * @param seed            seed of every random number in the run (sensor noise)
 * @param physicsHz       physics steps per simulated second
 * @param trajectories    how the robots' paths are sampled and how many points each keeps
 * @param engine          the physics engine that steps the world
 * @param source          the file, for messages
 * @param surroundings    water, wind, current and the world's place on Earth, for vehicles
 * @param swarms          the file's swarm entries, as written (their robots are among {@code robots}, after the
 *                        robots placed one by one, in the order of the entries)
 */
public record WorldDescription(String name, double width, double height, boolean walls, double wallThickness,
                               double floorBrightness, List<Obstacle> obstacles, List<FloorPatch> patches,
                               List<RobotPlacement> robots, long seed, double physicsHz, TrajectorySettings trajectories,
                               PhysicsEngine engine, String source, Surroundings surroundings, List<Swarm> swarms) {

    /** Copies the lists. */
    public WorldDescription {
        obstacles = List.copyOf(obstacles);
        patches = List.copyOf(patches);
        robots = List.copyOf(robots);
        java.util.Objects.requireNonNull(trajectories, "trajectories");
        java.util.Objects.requireNonNull(engine, "engine");
        java.util.Objects.requireNonNull(surroundings, "surroundings");
        swarms = List.copyOf(swarms);
    }

    /**
     * A world without swarm entries (every robot placed one by one).
     *
     * @param name            the world's name
     * @param width           arena width (x), metres
     * @param height          arena height (y), metres
     * @param walls           whether the arena is closed by walls
     * @param wallThickness   thickness of those walls, metres
     * @param floorBrightness brightness of the bare floor, 0 (black) to 1 (white)
     * @param obstacles       static obstacles
     * @param patches         floor patches seen by light and colour sensors
     * @param robots          the robots and where they start
     * @param seed            seed of every random number in the run (sensor noise)
     * @param physicsHz       physics steps per simulated second
     * @param trajectories    how the robots' paths are sampled and how many points each keeps
     * @param engine          the physics engine that steps the world
     * @param source          the file, for messages
     * @param surroundings    water, wind, current and the world's place on Earth, for vehicles
     */
    public WorldDescription(String name, double width, double height, boolean walls, double wallThickness,
                            double floorBrightness, List<Obstacle> obstacles, List<FloorPatch> patches,
                            List<RobotPlacement> robots, long seed, double physicsHz, TrajectorySettings trajectories,
                            PhysicsEngine engine, String source, Surroundings surroundings) {
        this(name, width, height, walls, wallThickness, floorBrightness, obstacles, patches, robots, seed, physicsHz, trajectories,
                engine, source, surroundings, List.of());
    }

    /**
     * A world without water, wind or current ({@link Surroundings#NONE}) or swarm entries.
     *
     * @param name            the world's name
     * @param width           arena width (x), metres
     * @param height          arena height (y), metres
     * @param walls           whether the arena is closed by walls
     * @param wallThickness   thickness of those walls, metres
     * @param floorBrightness brightness of the bare floor, 0 (black) to 1 (white)
     * @param obstacles       static obstacles
     * @param patches         floor patches seen by light and colour sensors
     * @param robots          the robots and where they start
     * @param seed            seed of every random number in the run (sensor noise)
     * @param physicsHz       physics steps per simulated second
     * @param trajectories    how the robots' paths are sampled and how many points each keeps
     * @param engine          the physics engine that steps the world
     * @param source          the file, for messages
     */
    public WorldDescription(String name, double width, double height, boolean walls, double wallThickness,
                            double floorBrightness, List<Obstacle> obstacles, List<FloorPatch> patches,
                            List<RobotPlacement> robots, long seed, double physicsHz, TrajectorySettings trajectories,
                            PhysicsEngine engine, String source) {
        this(name, width, height, walls, wallThickness, floorBrightness, obstacles, patches, robots, seed, physicsHz, trajectories,
                engine, source, Surroundings.NONE);
    }

    /**
     * What vehicles meet in a world besides its obstacles (the {@code water:}, {@code wind:},
     * {@code current:} and {@code home:} keys of a world file). Vectors are in the world's frame
     * (x east, y north), metres per second, the way the air or water moves.
     *
     * @param water   the areas of water a boat may be on (nowhere else)
     * @param windX   the wind's x, m/s
     * @param windY   the wind's y, m/s
     * @param currentX the water's current x, m/s
     * @param currentY the water's current y, m/s
     * @param home    where the world's origin (its lower-left corner) is on Earth
     */
    public record Surroundings(List<WaterArea> water, double windX, double windY, double currentX, double currentY, GeoOrigin home) {

        /** No water, still air and water; the origin at ArduPilot SITL's default home. */
        public static final Surroundings NONE = new Surroundings(List.of(), 0, 0, 0, 0, GeoOrigin.SITL_DEFAULT);

        /** Copies the list. */
        public Surroundings {
            water = List.copyOf(water);
            java.util.Objects.requireNonNull(home, "home");
        }

        /**
         * @param x a point's x
         * @param y a point's y
         * @return whether the point is on water
         */
        public boolean onWater(double x, double y) {
            for (WaterArea w : water) {
                if (w.contains(x, y)) {
                    return true;
                }
            }
            return false;
        }
    }

    /**
     * An area of water: a rectangle or a simple polygon (any shape; its points in either order).
     *
     * @param points the corners, {x, y} in world coordinates
     */
    public record WaterArea(List<double[]> points) {
        /** Copies. */
        public WaterArea {
            points = List.copyOf(points);
        }

        /**
         * @param x lower-left corner x
         * @param y lower-left corner y
         * @param width along x
         * @param height along y
         * @return a rectangle of water
         */
        public static WaterArea rectangle(double x, double y, double width, double height) {
            return new WaterArea(List.of(new double[]{x, y}, new double[]{x + width, y}, new double[]{x + width, y + height},
                    new double[]{x, y + height}));
        }

        /**
         * @param px a point's x
         * @param py a point's y
         * @return whether it is inside (even-odd rule)
         */
        public boolean contains(double px, double py) {
            boolean in = false;
            for (int i = 0, j = points.size() - 1; i < points.size(); j = i++) {
                double[] a = points.get(i);
                double[] b = points.get(j);
                if ((a[1] > py) != (b[1] > py) && px < (b[0] - a[0]) * (py - a[1]) / (b[1] - a[1]) + a[0]) {
                    in = !in;
                }
            }
            return in;
        }
    }

    /**
     * Where a world's origin is on Earth: its x axis points east, its y axis north, its z up.
     *
     * @param latitude  degrees, -90 to 90
     * @param longitude degrees, -180 to 180
     * @param altitude  metres above mean sea level
     */
    public record GeoOrigin(double latitude, double longitude, double altitude) {
        /** ArduPilot SITL's default home (CMAC, Canberra Model Aircraft Club): -35.363261, 149.165230, 584 m. */
        public static final GeoOrigin SITL_DEFAULT = new GeoOrigin(-35.363261, 149.165230, 584);

        /** Checks the ranges. */
        public GeoOrigin {
            if (!(Math.abs(latitude) <= 90) || !(Math.abs(longitude) <= 180) || !Double.isFinite(altitude)) {
                throw new IllegalArgumentException("a home is latitude -90..90, longitude -180..180 and a finite altitude, got "
                        + latitude + ", " + longitude + ", " + altitude);
            }
        }
    }

    /**
     * A world stepped by the default engine ({@link PhysicsEngine#DYN4J}).
     *
     * @param name            the world's name
     * @param width           arena width (x), metres
     * @param height          arena height (y), metres
     * @param walls           whether the arena is closed by walls
     * @param wallThickness   thickness of those walls, metres
     * @param floorBrightness brightness of the bare floor, 0 (black) to 1 (white)
     * @param obstacles       static obstacles
     * @param patches         floor patches seen by light and colour sensors
     * @param robots          the robots and where they start
     * @param seed            seed of every random number in the run (sensor noise)
     * @param physicsHz       physics steps per simulated second
     * @param trajectories    how the robots' paths are sampled and how many points each keeps
     * @param source          the file, for messages
     */
    public WorldDescription(String name, double width, double height, boolean walls, double wallThickness,
                            double floorBrightness, List<Obstacle> obstacles, List<FloorPatch> patches,
                            List<RobotPlacement> robots, long seed, double physicsHz, TrajectorySettings trajectories,
                            String source) {
        this(name, width, height, walls, wallThickness, floorBrightness, obstacles, patches, robots, seed, physicsHz,
                trajectories, PhysicsEngine.DYN4J, source);
    }

    /**
     * @param other another engine
     * @return this world stepped by that engine
     */
    public WorldDescription withEngine(PhysicsEngine other) {
        return new WorldDescription(name, width, height, walls, wallThickness, floorBrightness, obstacles, patches, robots, seed,
                physicsHz, trajectories, other, source, surroundings, swarms);
    }

    /** The physics engine that steps a world (the {@code physics: { engine: ... }} key of a world file). */
    public enum PhysicsEngine {
        /** The dyn4j library's general rigid-body world, on the stepping thread (the default). */
        DYN4J,
        /**
         * The simulator's own step for boxes on a flat floor, split between the world's worker
         * threads ({@link io.robomw.sim.physics.SwarmPhysics}).
         */
        SWARM
    }

    /**
     * A world whose trajectories are kept as {@link TrajectorySettings#DEFAULT} says.
     *
     * @param name            the world's name
     * @param width           arena width (x), metres
     * @param height          arena height (y), metres
     * @param walls           whether the arena is closed by walls
     * @param wallThickness   thickness of those walls, metres
     * @param floorBrightness brightness of the bare floor, 0 (black) to 1 (white)
     * @param obstacles       static obstacles
     * @param patches         floor patches seen by light and colour sensors
     * @param robots          the robots and where they start
     * @param seed            seed of every random number in the run (sensor noise)
     * @param physicsHz       physics steps per simulated second
     * @param source          the file, for messages
     */
    public WorldDescription(String name, double width, double height, boolean walls, double wallThickness,
                            double floorBrightness, List<Obstacle> obstacles, List<FloorPatch> patches,
                            List<RobotPlacement> robots, long seed, double physicsHz, String source) {
        this(name, width, height, walls, wallThickness, floorBrightness, obstacles, patches, robots, seed, physicsHz,
                TrajectorySettings.DEFAULT, source);
    }

    /**
     * How each robot's path is recorded (the {@code trajectory:} key of a world file): a point every
     * {@code everySeconds} of simulated time, at most {@code maxPoints} of them per robot, so a long
     * run's memory stays bounded.
     *
     * @param everySeconds simulated seconds between two samples (rounded to whole physics steps, at least one)
     * @param maxPoints    the most points kept per robot; 0 keeps none
     * @param keep         what a full trajectory gives up to make room
     */
    public record TrajectorySettings(double everySeconds, int maxPoints, Keep keep) {

        /** The most points a world file may ask for per robot. */
        public static final int MAX_POINTS = 1 << 20;

        /** A point every 0.1 s, at most 1000 points per robot (8 KB), the whole path thinned when full. */
        public static final TrajectorySettings DEFAULT = new TrajectorySettings(0.1, 1000, Keep.WHOLE);

        /** Checks the ranges. */
        public TrajectorySettings {
            if (!(everySeconds > 0) || everySeconds > 3600) {
                throw new IllegalArgumentException("trajectory sampling interval must be > 0 and at most 3600 s, got " + everySeconds);
            }
            if (maxPoints < 0 || maxPoints > MAX_POINTS) {
                throw new IllegalArgumentException("trajectory points must be 0 to " + MAX_POINTS + ", got " + maxPoints);
            }
            java.util.Objects.requireNonNull(keep, "keep");
        }
    }

    /** What a trajectory that holds its most points gives up for the next one. */
    public enum Keep {
        /**
         * The whole path, ever coarser: every other point is dropped and from then on the path is
         * sampled half as often, so it always spans the whole run with between half and all of the
         * points allowed.
         */
        WHOLE,
        /** Only the most recent points: the oldest point is dropped for each new one. */
        RECENT
    }

    /** A static obstacle. */
    public sealed interface Obstacle permits Box, Circle, Polygon {
    }

    /**
     * A rectangle.
     *
     * @param x      centre x
     * @param y      centre y
     * @param width  along its own x axis
     * @param height along its own y axis
     * @param angle  rotation, radians
     */
    public record Box(double x, double y, double width, double height, double angle) implements Obstacle {
    }

    /**
     * A disc.
     *
     * @param x      centre x
     * @param y      centre y
     * @param radius radius
     */
    public record Circle(double x, double y, double radius) implements Obstacle {
    }

    /**
     * A convex polygon, vertices anti-clockwise.
     *
     * @param points vertices as {x, y} pairs, in world coordinates
     */
    public record Polygon(List<double[]> points) implements Obstacle {
        /** Copies. */
        public Polygon {
            points = List.copyOf(points);
        }
    }

    /**
     * A rectangle of floor with its own brightness and colour.
     *
     * @param x          lower-left corner x
     * @param y          lower-left corner y
     * @param width      along x
     * @param height     along y
     * @param brightness 0 (black) to 1 (white)
     * @param color      colour number reported by colour sensors
     */
    public record FloorPatch(double x, double y, double width, double height, double brightness, int color) {
        /**
         * @param px a point's x
         * @param py a point's y
         * @return whether the point is on this patch
         */
        public boolean contains(double px, double py) {
            return px >= x && px <= x + width && py >= y && py <= y + height;
        }
    }

    /**
     * A robot in the world.
     *
     * @param description its robot YAML file
     * @param name        its name in this world (defaults to the file's name; unique)
     * @param start       where it starts
     */
    public record RobotPlacement(Path description, String name, Pose start) {
    }

    /**
     * A swarm entry of a world file: {@code count} robots from one robot file, named
     * {@code <name>-1} to {@code <name>-<count>}, placed by {@code seed} in a rectangle of the arena
     * (see {@code docs/simulation.md}, "Swarms").
     *
     * @param robot  the robot YAML file every robot of the swarm is read from
     * @param name   the robots' names' stem
     * @param count  how many robots
     * @param x      the area's lower-left corner x, metres
     * @param y      its lower-left corner y
     * @param width  its extent along x, metres
     * @param height its extent along y
     * @param seed   the seed of the places and headings
     * @param first  the index of its first robot in {@link WorldDescription#robots()}
     */
    public record Swarm(Path robot, String name, int count, double x, double y, double width, double height, long seed, int first) {
    }
}
