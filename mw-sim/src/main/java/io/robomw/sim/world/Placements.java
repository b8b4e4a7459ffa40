package io.robomw.sim.world;

import io.robomw.config.yaml.Problems;
import org.dyn4j.collision.CollisionPair;
import org.dyn4j.collision.broadphase.AABBProducer;
import org.dyn4j.collision.broadphase.BroadphaseDetector;
import org.dyn4j.collision.broadphase.DynamicAABBTree;
import org.dyn4j.collision.broadphase.NullAABBExpansionMethod;
import org.dyn4j.collision.narrowphase.Penetration;
import org.dyn4j.collision.narrowphase.Sat;
import org.dyn4j.geometry.AABB;
import org.dyn4j.geometry.Convex;
import org.dyn4j.geometry.Geometry;
import org.dyn4j.geometry.Transform;
import org.dyn4j.geometry.Vector2;
import org.yaml.snakeyaml.error.Mark;

import java.util.ArrayList;
import java.util.HashSet;
import java.util.Iterator;
import java.util.List;
import java.util.Locale;
import java.util.Set;

/**
 * Where a world file puts things at the start: each robot must be clear of every wall, obstacle
 * and other robot, or the physics would push them apart at the first step (dyn4j and the swarm
 * engine alike), and the world would start elsewhere than its file says. A robot overlapping
 * something by more than {@value #TOLERANCE_METRES} m is a problem at the robot's place in the
 * file, naming the two things and how deep they overlap.
 *
 * <p>The shapes are dyn4j's; candidate pairs come from dyn4j's broadphase (a dynamic AABB tree), so
 * a world of 10,000 robots is checked in about n log n, not n², and each candidate by its
 * separating-axis test. Not thread-safe; one per load.
 */
final class Placements {

    /** How deep two things may overlap at the start and still be accepted (a placement rounded to the millimetre), metres. */
    static final double TOLERANCE_METRES = 0.001;

    /** One thing placed: a robot's body, an obstacle or a wall. */
    private record Placed(int index, boolean robot, String name, String path, Mark mark, Convex shape, Transform transform) {
        /** @return the item as a message names it, with where it is in the file */
        String where() {
            return name + " (" + (path.isEmpty() ? "" : path + ", ") + "line " + (mark.getLine() + 1) + ")";
        }

        // One item is one place in the list: the broadphase's map keys it by its index, not by hashing
        // its name, shape and transform (most of the check's time for a swarm of 100,000 robots).

        @Override
        public boolean equals(Object o) {
            return o instanceof Placed p && p.index == index;
        }

        @Override
        public int hashCode() {
            return Integer.hashCode(index);
        }
    }

    private final List<Placed> placed = new ArrayList<>();
    private long narrowphaseTests;

    /**
     * A box: a wall or an obstacle.
     *
     * @param name  what it is called in messages ({@code the arena's left wall (x < 0)})
     * @param path  its path in the file ({@code obstacles[2]})
     * @param mark  where it is in the file
     * @param x     centre x
     * @param y     centre y
     * @param width along x before the rotation
     * @param height along y before the rotation
     * @param angle rotation, radians
     */
    void box(String name, String path, Mark mark, double x, double y, double width, double height, double angle) {
        add(false, name, path, mark, Geometry.createRectangle(width, height), x, y, angle);
    }

    /** A disc obstacle; the parameters as for {@link #box}. */
    void circle(String name, String path, Mark mark, double x, double y, double radius) {
        add(false, name, path, mark, Geometry.createCircle(radius), x, y, 0);
    }

    /** A convex polygon obstacle, vertices anti-clockwise in world coordinates; the others as for {@link #box}. */
    void polygon(String name, String path, Mark mark, List<double[]> points) {
        Vector2[] v = points.stream().map(p -> new Vector2(p[0], p[1])).toArray(Vector2[]::new);
        add(false, name, path, mark, Geometry.createPolygon(v), 0, 0, 0);
    }

    /**
     * A robot's body, a rectangle {@code length} along its heading and {@code width} across it,
     * centred where it starts, heading anti-clockwise from x; the others as for {@link #box}.
     */
    void robot(String name, String path, Mark mark, double length, double width, double x, double y, double heading) {
        add(true, name, path, mark, Geometry.createRectangle(length, width), x, y, heading);
    }

    private void add(boolean robot, String name, String path, Mark mark, Convex shape, double x, double y, double angle) {
        Transform t = new Transform();
        t.rotate(angle);
        t.translate(x, y);
        placed.add(new Placed(placed.size(), robot, name, path, mark, shape, t));
    }

    /**
     * Reports every robot that overlaps something, at the robot's place in the file (of two
     * robots, the later one).
     *
     * @param problems where they go
     */
    void check(Problems problems) {
        AABBProducer<Placed> aabbs = new AABBProducer<>() {
            @Override
            public AABB compute(Placed p) {
                return p.shape().createAABB(p.transform());
            }

            @Override
            public void compute(Placed p, AABB into) {
                p.shape().computeAABB(p.transform(), into);
            }
        };
        // Walls and obstacles may overlap each other (a box on a wall): only pairs with a robot count (and the tree pairs an item with itself).
        BroadphaseDetector<Placed> broadphase = new DynamicAABBTree<>((a, b) -> a != b && (a.robot() || b.robot()), aabbs, new NullAABBExpansionMethod<>());
        for (Placed p : placed) {
            broadphase.add(p);
        }
        Sat sat = new Sat();
        Penetration penetration = new Penetration();
        Set<Long> reported = new HashSet<>();
        for (Iterator<CollisionPair<Placed>> it = broadphase.detectIterator(true); it.hasNext(); ) {
            CollisionPair<Placed> pair = it.next();
            Placed a = pair.getFirst();
            Placed b = pair.getSecond();
            narrowphaseTests++;
            penetration.clear();
            if (!sat.detect(a.shape(), a.transform(), b.shape(), b.transform(), penetration) || penetration.getDepth() <= TOLERANCE_METRES) {
                continue;
            }
            Placed later = !a.robot() ? b : !b.robot() ? a : a.index() > b.index() ? a : b;
            Placed other = later == a ? b : a;
            if (!reported.add((long) Math.min(a.index(), b.index()) << 32 | Math.max(a.index(), b.index()))) {
                continue;
            }
            problems.add(later.mark(), String.format(Locale.ROOT,
                    "'%s': %s %s %s by %.1f cm at the start; place it clear of it (the physics would push them apart at the first step, "
                            + "and the world would start elsewhere than this file says)",
                    later.path(), later.name(), other.robot() ? "overlaps" : "starts inside", other.where(), penetration.getDepth() * 100));
        }
    }

    /** @return how many candidate pairs the separating-axis test looked at (the broadphase's output) */
    long narrowphaseTests() {
        return narrowphaseTests;
    }
}
