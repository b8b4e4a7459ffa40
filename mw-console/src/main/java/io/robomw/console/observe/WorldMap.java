package io.robomw.console.observe;

import io.robomw.api.Pose;
import io.robomw.sim.SimRobot;
import io.robomw.sim.SimWorld;
import io.robomw.sim.world.WorldDescription;

import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

/**
 * A world's map as the console draws it and a recording keeps it: the arena, its obstacles and
 * floor patches, and the robots' footprints. Metres, radians, origin at the arena's lower-left
 * corner.
 *
 * @param name            the world's name
 * @param width           arena width
 * @param height          arena height
 * @param walls           whether walls close it
 * @param wallThickness   their thickness
 * @param floorBrightness 0 black to 1 white
 * @param obstacles       boxes, circles and polygons
 * @param patches         floor patches
 * @param robots          the robots, their footprints and start poses
 * @param water           the areas of water boats sail on, each a polygon of [x, y] points (none in
 *                        recordings made before vehicles: read as none)
 */
public record WorldMap(String name, double width, double height, boolean walls, double wallThickness, double floorBrightness,
                       List<Shape> obstacles, List<Patch> patches, List<RobotMark> robots, List<List<double[]>> water) {

    /** Copies. */
    public WorldMap {
        obstacles = List.copyOf(obstacles);
        patches = List.copyOf(patches);
        robots = List.copyOf(robots);
        water = water == null ? List.of() : water.stream().map(List::copyOf).toList();
    }

    /** A map without water. */
    public WorldMap(String name, double width, double height, boolean walls, double wallThickness, double floorBrightness,
                    List<Shape> obstacles, List<Patch> patches, List<RobotMark> robots) {
        this(name, width, height, walls, wallThickness, floorBrightness, obstacles, patches, robots, List.of());
    }

    /**
     * An obstacle.
     *
     * @param kind   "box", "circle" or "polygon"
     * @param x      centre x (box, circle)
     * @param y      centre y
     * @param width  box width, or circle diameter
     * @param height box height, or circle diameter
     * @param angle  box rotation
     * @param points polygon vertices, [x, y] pairs
     */
    public record Shape(String kind, double x, double y, double width, double height, double angle, List<double[]> points) {
        /** Copies. */
        public Shape {
            points = List.copyOf(points);
        }
    }

    /** A floor patch: lower-left corner, size, brightness 0..1. */
    public record Patch(double x, double y, double width, double height, double brightness) {
    }

    /** A robot: its footprint (length along its heading, width across) and where it starts. */
    public record RobotMark(String name, double length, double width, double startX, double startY, double startHeading) {
    }

    /**
     * @param world a simulated world
     * @return its map
     */
    public static WorldMap of(SimWorld world) {
        WorldDescription d = world.description();
        List<RobotMark> robots = new ArrayList<>();
        for (SimRobot r : world.robots()) {
            Pose start = d.robots().stream().filter(p -> p.name().equals(r.name())).findFirst().map(WorldDescription.RobotPlacement::start)
                    .orElse(r.pose());
            robots.add(new RobotMark(r.name(), r.description().body().length(), r.description().body().width(), start.x(), start.y(), start.heading()));
        }
        return of(d, robots);
    }

    /**
     * @param d      a world file's description
     * @param robots its robots' marks
     * @return its map
     */
    public static WorldMap of(WorldDescription d, List<RobotMark> robots) {
        List<Shape> shapes = new ArrayList<>();
        for (WorldDescription.Obstacle o : d.obstacles()) {
            if (o instanceof WorldDescription.Box b) {
                shapes.add(new Shape("box", b.x(), b.y(), b.width(), b.height(), b.angle(), List.of()));
            } else if (o instanceof WorldDescription.Circle c) {
                shapes.add(new Shape("circle", c.x(), c.y(), 2 * c.radius(), 2 * c.radius(), 0, List.of()));
            } else if (o instanceof WorldDescription.Polygon p) {
                shapes.add(new Shape("polygon", 0, 0, 0, 0, 0, p.points()));
            }
        }
        List<Patch> patches = d.patches().stream().map(p -> new Patch(p.x(), p.y(), p.width(), p.height(), p.brightness())).toList();
        List<List<double[]>> water = d.surroundings().water().stream().map(WorldDescription.WaterArea::points).toList();
        return new WorldMap(d.name(), d.width(), d.height(), d.walls(), d.wallThickness(), d.floorBrightness(), shapes, patches, robots, water);
    }

    /**
     * A robot's odometry counts from where it started; on this map, a robot with a mark of its name
     * is placed from its start pose: the start, then the odometry in the start's frame. True poses
     * (and robots without a mark) are the map's already. The live page and replays (the page, the
     * picture) place poses so, so a recording shows a robot where the live console showed it.
     *
     * @param p a pose as observed
     * @return it in the map's frame
     */
    public Observation.RobotPose placed(Observation.RobotPose p) {
        if (p.truth()) {
            return p;
        }
        for (RobotMark m : robots) {
            if (m.name().equals(p.robot())) {
                double c = Math.cos(m.startHeading());
                double s = Math.sin(m.startHeading());
                return new Observation.RobotPose(p.timeNanos(), p.robot(), m.startX() + c * p.x() - s * p.y(), m.startY() + s * p.x() + c * p.y(),
                        p.z(), m.startHeading() + p.heading(), false);
            }
        }
        return p;
    }

    /** @return the description this map was made from, as far as drawing needs it (robot files unknown) */
    public WorldDescription description() {
        List<WorldDescription.Obstacle> obstacles = new ArrayList<>();
        for (Shape s : obstacles()) {
            switch (s.kind()) {
                case "box" -> obstacles.add(new WorldDescription.Box(s.x(), s.y(), s.width(), s.height(), s.angle()));
                case "circle" -> obstacles.add(new WorldDescription.Circle(s.x(), s.y(), s.width() / 2));
                case "polygon" -> obstacles.add(new WorldDescription.Polygon(s.points()));
                default -> throw new IllegalArgumentException("obstacle kind '" + s.kind() + "' is not box, circle or polygon");
            }
        }
        List<WorldDescription.FloorPatch> floor = patches().stream()
                .map(p -> new WorldDescription.FloorPatch(p.x(), p.y(), p.width(), p.height(), p.brightness(), 0)).toList();
        List<WorldDescription.RobotPlacement> placed = robots().stream()
                .map(r -> new WorldDescription.RobotPlacement(Path.of("recorded"), r.name(), new Pose(r.startX(), r.startY(), r.startHeading()))).toList();
        WorldDescription.Surroundings surroundings = new WorldDescription.Surroundings(water.stream().map(WorldDescription.WaterArea::new).toList(),
                0, 0, 0, 0, WorldDescription.GeoOrigin.SITL_DEFAULT);
        return new WorldDescription(name, width, height, walls, wallThickness, floorBrightness, obstacles, floor, placed, 0, 60,
                WorldDescription.TrajectorySettings.DEFAULT, WorldDescription.PhysicsEngine.DYN4J, "recording", surroundings);
    }
}
