package io.robomw.sim.render;

import io.robomw.api.Pose;
import io.robomw.config.description.Body;
import io.robomw.sim.SensorModel;
import io.robomw.sim.SimRobot;
import io.robomw.sim.SimWorld;
import io.robomw.sim.legged.Quadruped;
import io.robomw.sim.world.WorldDescription;

import java.awt.BasicStroke;
import java.awt.Color;
import java.awt.Font;
import java.awt.FontMetrics;
import java.awt.Graphics2D;
import java.awt.RenderingHints;
import java.awt.Shape;
import java.awt.geom.Ellipse2D;
import java.awt.geom.Line2D;
import java.awt.geom.Path2D;
import java.awt.geom.Rectangle2D;
import java.util.List;
import java.util.Locale;

/**
 * Draws a simulated world with Java2D: the one drawing code of both the PNG renderer and the
 * viewer. Paints, in this order: the background, the arena floor, floor patches (grey by
 * brightness), water (blue), walls, obstacles, trajectories (a flyer's dashed), sensor rays, robots
 * (oriented bodies with a heading mark; a flyer with its rotors), name labels (a flyer's with its
 * altitude), then the world's name, time, wind and current, and a scale bar.
 *
 * <p>Reads only what may be read while the simulation thread steps (each robot's pose, trajectory
 * and latest range readings, and the world's time), so a viewer may paint from the Swing thread
 * during a real-time run. Stateless apart from its options; one instance may paint many frames.
 */
public final class WorldPainter {

    private static final Color BACKGROUND = new Color(0xF4F4F2);
    private static final Color WALL = new Color(0x3C4048);
    private static final Color OBSTACLE_FILL = new Color(0x8A7F72);
    private static final Color OBSTACLE_EDGE = new Color(0x4A433B);
    private static final Color ROBOT_EDGE = new Color(0x202020);
    private static final Color RAY_HIT = new Color(220, 30, 30, 170);
    private static final Color RAY_FREE = new Color(40, 150, 60, 150);
    private static final Color TEXT = new Color(0x202020);
    private static final Color WATER = new Color(0x9CC7E4);
    private static final Color WATER_EDGE = new Color(0x5B95BF);
    private static final Color HALO = new Color(255, 255, 255, 150);
    /** Distinct colours for the first robots (the Tableau 10 palette without its grey); later robots get spread hues. */
    private static final int[] PALETTE = {0x4E79A7, 0xF28E2B, 0xE15759, 0x59A14F, 0xB07AA1, 0x76B7B2, 0xEDC948, 0xFF9DA7, 0x9C755F};
    private static final double GOLDEN_RATIO_CONJUGATE = 0.618_033_988_749_895;
    /** A robot smaller than this on screen is drawn as a dot of this diameter, pixels. */
    private static final double MIN_ROBOT_PX = 4;
    /** Robots above this count get thinner paths, so a swarm's paths do not merge into one blot. */
    private static final int CROWD = 200;

    private final RenderOptions options;

    /**
     * @param options what to show
     */
    public WorldPainter(RenderOptions options) {
        this.options = options;
    }

    /** @return what it shows */
    public RenderOptions options() {
        return options;
    }

    /**
     * @param world a world
     * @return the world rectangle a picture must show: the arena with its walls, metres
     */
    public static Rectangle2D bounds(WorldDescription world) {
        double t = world.walls() ? world.wallThickness() : 0;
        return new Rectangle2D.Double(-t, -t, world.width() + 2 * t, world.height() + 2 * t);
    }

    /**
     * @param world    a world
     * @param widthPx  image width
     * @param heightPx image height
     * @param marginPx free pixels on every side
     * @return the transform that shows the whole arena, centred
     */
    public static ViewTransform fit(WorldDescription world, int widthPx, int heightPx, int marginPx) {
        Rectangle2D b = bounds(world);
        return ViewTransform.fit(b.getMinX(), b.getMinY(), b.getMaxX(), b.getMaxY(), widthPx, heightPx, marginPx);
    }

    /**
     * @param robotIndex a robot's index in its world
     * @return the colour of its body and path: distinct for neighbouring indices
     */
    public static Color robotColor(int robotIndex) {
        if (robotIndex < PALETTE.length) {
            return new Color(PALETTE[robotIndex]);
        }
        float hue = (float) ((robotIndex * GOLDEN_RATIO_CONJUGATE) % 1.0);
        return Color.getHSBColor(hue, 0.70f, 0.85f);
    }

    /**
     * Paints the whole picture.
     *
     * @param g        where to paint; its transform is left as it was
     * @param world    the world
     * @param view     world-to-screen mapping
     * @param widthPx  width of the area to fill, pixels
     * @param heightPx height of the area to fill, pixels
     */
    public void paint(Graphics2D g, SimWorld world, ViewTransform view, int widthPx, int heightPx) {
        g.setRenderingHint(RenderingHints.KEY_ANTIALIASING, RenderingHints.VALUE_ANTIALIAS_ON);
        g.setRenderingHint(RenderingHints.KEY_TEXT_ANTIALIASING, RenderingHints.VALUE_TEXT_ANTIALIAS_ON);
        g.setRenderingHint(RenderingHints.KEY_STROKE_CONTROL, RenderingHints.VALUE_STROKE_PURE);
        g.setColor(BACKGROUND);
        g.fillRect(0, 0, widthPx, heightPx);
        WorldDescription d = world.description();
        paintArena(g, d, view);
        List<SimRobot> robots = world.robots();
        if (options.showTrajectories()) {
            float width = robots.size() > CROWD ? 1f : 2f;
            BasicStroke line = new BasicStroke(width, BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND);
            BasicStroke halo = new BasicStroke(width + 2.5f, BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND);
            for (SimRobot r : robots) {
                paintTrajectory(g, r, view, line, halo);
            }
        }
        if (options.showRays()) {
            g.setStroke(new BasicStroke(1f));
            for (SimRobot r : robots) {
                paintRays(g, r, view);
            }
        }
        for (SimRobot r : robots) {
            paintRobot(g, r, view);
        }
        if (robots.size() <= options.labelLimit()) {
            g.setFont(new Font(Font.SANS_SERIF, Font.PLAIN, 12));
            for (SimRobot r : robots) {
                paintLabel(g, r, view);
            }
        }
        paintCaption(g, world, view, heightPx);
    }

    /**
     * Paints the arena alone: walls, floor, floor patches and obstacles (a replayed recording
     * draws its own trajectories over it).
     *
     * @param g    where to paint
     * @param d    the world
     * @param view world-to-screen mapping
     */
    public static void paintArena(Graphics2D g, WorldDescription d, ViewTransform view) {
        if (d.walls()) {
            g.setColor(WALL);
            g.fill(rect(view, bounds(d)));
        }
        g.setColor(grey(d.floorBrightness()));
        g.fill(rect(view, new Rectangle2D.Double(0, 0, d.width(), d.height())));
        for (WorldDescription.FloorPatch p : d.patches()) {
            g.setColor(grey(p.brightness()));
            g.fill(rect(view, new Rectangle2D.Double(p.x(), p.y(), p.width(), p.height())));
        }
        g.setStroke(new BasicStroke(1f));
        for (WorldDescription.WaterArea w : d.surroundings().water()) {
            Path2D.Double path = new Path2D.Double();
            List<double[]> points = w.points();
            path.moveTo(view.screenX(points.get(0)[0]), view.screenY(points.get(0)[1]));
            for (double[] xy : points.subList(1, points.size())) {
                path.lineTo(view.screenX(xy[0]), view.screenY(xy[1]));
            }
            path.closePath();
            g.setColor(WATER);
            g.fill(path);
            g.setColor(WATER_EDGE);
            g.draw(path);
        }
        g.setStroke(new BasicStroke(1.5f));
        for (WorldDescription.Obstacle o : d.obstacles()) {
            Shape s = obstacle(o, view);
            g.setColor(OBSTACLE_FILL);
            g.fill(s);
            g.setColor(OBSTACLE_EDGE);
            g.draw(s);
        }
    }

    private static Shape obstacle(WorldDescription.Obstacle o, ViewTransform view) {
        if (o instanceof WorldDescription.Box b) {
            return orientedRect(view, b.x(), b.y(), b.angle(), b.width(), b.height());
        }
        if (o instanceof WorldDescription.Circle c) {
            double r = c.radius() * view.scale();
            return new Ellipse2D.Double(view.screenX(c.x()) - r, view.screenY(c.y()) - r, 2 * r, 2 * r);
        }
        WorldDescription.Polygon p = (WorldDescription.Polygon) o;
        Path2D.Double path = new Path2D.Double();
        List<double[]> points = p.points();
        path.moveTo(view.screenX(points.get(0)[0]), view.screenY(points.get(0)[1]));
        for (double[] xy : points.subList(1, points.size())) {
            path.lineTo(view.screenX(xy[0]), view.screenY(xy[1]));
        }
        path.closePath();
        return path;
    }

    private static void paintTrajectory(Graphics2D g, SimRobot r, ViewTransform view, BasicStroke line, BasicStroke halo) {
        double[] points = r.trajectory().snapshot();
        Pose now = r.pose();
        Path2D.Double path = new Path2D.Double();
        double lastX = view.screenX(points.length >= 2 ? points[0] : now.x());
        double lastY = view.screenY(points.length >= 2 ? points[1] : now.y());
        path.moveTo(lastX, lastY);
        for (int i = 2; i + 1 < points.length; i += 2) {
            double x = view.screenX(points[i]);
            double y = view.screenY(points[i + 1]);
            // Points closer than a pixel add nothing to the picture but cost time in long runs.
            if (Math.abs(x - lastX) + Math.abs(y - lastY) >= 1) {
                path.lineTo(x, y);
                lastX = x;
                lastY = y;
            }
        }
        path.lineTo(view.screenX(now.x()), view.screenY(now.y()));
        // A pale edge keeps the path visible where it crosses a dark floor patch.
        g.setColor(HALO);
        g.setStroke(halo);
        g.draw(path);
        g.setColor(robotColor(r.index()));
        g.setStroke(flyer(r) ? new BasicStroke(line.getLineWidth(), BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND, 1f,
                new float[]{6f, 4f}, 0f) : line);
        g.draw(path);
    }

    /** @return whether a robot is a vehicle of the air */
    private static boolean flyer(SimRobot r) {
        return r.vehicle() != null && r.vehicle().medium() == io.robomw.config.description.VehicleDrive.Medium.AIR;
    }

    private static void paintRays(Graphics2D g, SimRobot r, ViewTransform view) {
        Pose p = r.pose();
        double c = Math.cos(p.heading());
        double s = Math.sin(p.heading());
        for (SensorModel m : r.rangeSensors()) {
            double ox = p.x() + m.mountX() * c - m.mountY() * s;
            double oy = p.y() + m.mountX() * s + m.mountY() * c;
            double a = p.heading() + m.mountAngle();
            double range = r.latest(m);
            double ex = ox + range * Math.cos(a);
            double ey = oy + range * Math.sin(a);
            boolean hit = range < m.maxRange();
            g.setColor(hit ? RAY_HIT : RAY_FREE);
            g.draw(new Line2D.Double(view.screenX(ox), view.screenY(oy), view.screenX(ex), view.screenY(ey)));
            if (hit) {
                g.fill(new Ellipse2D.Double(view.screenX(ex) - 2, view.screenY(ey) - 2, 4, 4));
            }
        }
    }

    private static void paintRobot(Graphics2D g, SimRobot r, ViewTransform view) {
        Pose p = r.pose();
        Body b = r.description().body();
        Color color = robotColor(r.index());
        double sx = view.screenX(p.x());
        double sy = view.screenY(p.y());
        if (Math.max(b.length(), b.width()) * view.scale() < MIN_ROBOT_PX) {
            g.setColor(color.darker());
            g.fill(new Ellipse2D.Double(sx - MIN_ROBOT_PX / 2, sy - MIN_ROBOT_PX / 2, MIN_ROBOT_PX, MIN_ROBOT_PX));
            return;
        }
        if (r.quadruped() != null) {
            paintLegs(g, r, view, p, b, color);
        }
        if (flyer(r)) {
            paintRotors(g, view, p, b, color);
        }
        Shape body = orientedRect(view, p.x(), p.y(), p.heading(), b.length(), b.width());
        g.setColor(color);
        g.fill(body);
        g.setColor(ROBOT_EDGE);
        g.setStroke(new BasicStroke(1.5f));
        g.draw(body);
        double frontX = p.x() + b.length() / 2 * Math.cos(p.heading());
        double frontY = p.y() + b.length() / 2 * Math.sin(p.heading());
        g.setStroke(new BasicStroke(2.5f, BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND));
        g.draw(new Line2D.Double(sx, sy, view.screenX(frontX), view.screenY(frontY)));
    }

    /**
     * A legged robot from above: four legs out of the trunk's corners, each swung forwards or back
     * by its shoulder or hip joint as the gait moves it, a head at the front turned by its pan, and
     * a tail. Drawn under the trunk.
     */
    private static void paintLegs(Graphics2D g, SimRobot r, ViewTransform view, Pose p, Body b, Color color) {
        Quadruped dog = r.quadruped();
        double c = Math.cos(p.heading());
        double s = Math.sin(p.heading());
        double legLength = b.width() * 0.45;
        g.setColor(color.darker());
        g.setStroke(new BasicStroke((float) Math.max(1.5, b.width() * 0.12 * view.scale()), BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND));
        String[] legs = {"LF", "RF", "LH", "RH"};
        for (String leg : legs) {
            double lx = (leg.endsWith("F") ? 0.35 : -0.35) * b.length();
            double ly = (leg.startsWith("L") ? 0.5 : -0.5) * b.width();
            double swing = Math.toRadians(dog.joint("leg" + leg + "1").angle());
            double ex = lx + legLength * Math.sin(swing) * 0.8;
            double ey = ly + Math.signum(ly) * legLength * Math.cos(swing) * 0.6;
            g.draw(new Line2D.Double(view.screenX(p.x() + lx * c - ly * s), view.screenY(p.y() + lx * s + ly * c),
                    view.screenX(p.x() + ex * c - ey * s), view.screenY(p.y() + ex * s + ey * c)));
        }
        double pan = Math.toRadians(dog.joint("headPan").angle());
        double neck = b.length() / 2;
        double headRadius = b.width() * 0.32;
        double hx = neck + headRadius * 0.6 * Math.cos(pan);
        double hy = headRadius * 0.6 * Math.sin(pan);
        double wx = p.x() + hx * c - hy * s;
        double wy = p.y() + hx * s + hy * c;
        double rpx = headRadius * view.scale();
        g.fill(new Ellipse2D.Double(view.screenX(wx) - rpx, view.screenY(wy) - rpx, 2 * rpx, 2 * rpx));
        double tail = Math.toRadians(dog.joint("tailPan").angle());
        double tx = -b.length() / 2 - b.width() * 0.4 * Math.cos(tail);
        double ty = -b.width() * 0.4 * Math.sin(tail);
        g.draw(new Line2D.Double(view.screenX(p.x() - b.length() / 2 * c), view.screenY(p.y() - b.length() / 2 * s),
                view.screenX(p.x() + tx * c - ty * s), view.screenY(p.y() + tx * s + ty * c)));
    }

    /** A multirotor from above: four rotor discs at the body's corners, drawn under it. */
    private static void paintRotors(Graphics2D g, ViewTransform view, Pose p, Body b, Color color) {
        double c = Math.cos(p.heading());
        double s = Math.sin(p.heading());
        double r = Math.min(b.length(), b.width()) * 0.3 * view.scale();
        g.setStroke(new BasicStroke(1.2f));
        for (double[] corner : new double[][]{{0.5, 0.5}, {0.5, -0.5}, {-0.5, 0.5}, {-0.5, -0.5}}) {
            double lx = corner[0] * b.length();
            double ly = corner[1] * b.width();
            double x = view.screenX(p.x() + lx * c - ly * s);
            double y = view.screenY(p.y() + lx * s + ly * c);
            g.setColor(new Color(color.getRed(), color.getGreen(), color.getBlue(), 90));
            g.fill(new Ellipse2D.Double(x - r, y - r, 2 * r, 2 * r));
            g.setColor(ROBOT_EDGE);
            g.draw(new Ellipse2D.Double(x - r, y - r, 2 * r, 2 * r));
        }
    }

    private static void paintLabel(Graphics2D g, SimRobot r, ViewTransform view) {
        Pose p = r.pose();
        Body b = r.description().body();
        double radiusPx = Math.hypot(b.length(), b.width()) / 2 * view.scale();
        float x = (float) (view.screenX(p.x()) + radiusPx + 3);
        float y = (float) (view.screenY(p.y()) - radiusPx - 3);
        g.setColor(HALO);
        String label = flyer(r) ? String.format(Locale.ROOT, "%s  %.1f m", r.name(), r.vehicle().snapshot().z()) : r.name();
        for (int[] d : new int[][]{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
            g.drawString(label, x + d[0], y + d[1]);
        }
        g.setColor(TEXT);
        g.drawString(label, x, y);
    }

    /** The world's name and time in the top-left corner, a scale bar in the bottom-left one. */
    private static void paintCaption(Graphics2D g, SimWorld world, ViewTransform view, int heightPx) {
        g.setFont(new Font(Font.SANS_SERIF, Font.BOLD, 13));
        FontMetrics fm = g.getFontMetrics();
        WorldDescription.Surroundings around = world.description().surroundings();
        String caption = String.format(Locale.ROOT, "%s   t = %.1f s", world.description().name(), world.time())
                + flow("wind", around.windX(), around.windY()) + flow("current", around.currentX(), around.currentY());
        // A pale box under the text keeps it readable when the view is zoomed onto the arena.
        g.setColor(HALO);
        g.fill(new Rectangle2D.Double(4, 2, fm.stringWidth(caption) + 8, fm.getHeight() + 2));
        g.setColor(TEXT);
        g.drawString(caption, 8, 3 + fm.getAscent());
        double metres = scaleBarMetres(view.scale());
        double px = metres * view.scale();
        int y = heightPx - 8;
        g.setFont(new Font(Font.SANS_SERIF, Font.PLAIN, 11));
        String label = scaleLabel(metres);
        g.setColor(HALO);
        g.fill(new Rectangle2D.Double(4, y - 14, px + 16 + g.getFontMetrics().stringWidth(label), 20));
        g.setColor(TEXT);
        g.setStroke(new BasicStroke(2f));
        g.draw(new Line2D.Double(8, y, 8 + px, y));
        g.draw(new Line2D.Double(8, y - 4, 8, y));
        g.draw(new Line2D.Double(8 + px, y - 4, 8 + px, y));
        g.drawString(label, (float) (14 + px), y + 1);
    }

    /** @return {@code "   wind 1.5 m/s toward 90°"} (a compass bearing), or "" when still */
    private static String flow(String what, double x, double y) {
        double speed = Math.hypot(x, y);
        if (speed == 0) {
            return "";
        }
        double bearing = (Math.toDegrees(Math.atan2(x, y)) + 360) % 360;
        return String.format(Locale.ROOT, "   %s %.2f m/s toward %.0f°", what, speed, bearing);
    }

    /**
     * @param pixelsPerMetre the scale
     * @return a round length (1, 2 or 5 times a power of ten metres) between 60 and 150 pixels long
     */
    static double scaleBarMetres(double pixelsPerMetre) {
        double target = 100 / pixelsPerMetre;
        double power = Math.pow(10, Math.floor(Math.log10(target)));
        double m = target / power;
        double step = m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10;
        return step * power;
    }

    private static String scaleLabel(double metres) {
        if (metres >= 1000) {
            return String.format(Locale.ROOT, "%.0f km", metres / 1000);
        }
        if (metres >= 1) {
            return String.format(Locale.ROOT, "%.0f m", metres);
        }
        if (metres >= 0.01) {
            return String.format(Locale.ROOT, "%.0f cm", metres * 100);
        }
        return String.format(Locale.ROOT, "%.1f mm", metres * 1000);
    }

    private static Color grey(double brightness) {
        int v = (int) Math.round(Math.max(0, Math.min(1, brightness)) * 255);
        return new Color(v, v, v);
    }

    private static Shape rect(ViewTransform view, Rectangle2D world) {
        double x = view.screenX(world.getMinX());
        double y = view.screenY(world.getMaxY());
        return new Rectangle2D.Double(x, y, world.getWidth() * view.scale(), world.getHeight() * view.scale());
    }

    /** A rectangle of the given size centred at (x, y), its length along {@code angle}, in screen coordinates. */
    private static Path2D orientedRect(ViewTransform view, double x, double y, double angle, double length, double width) {
        double c = Math.cos(angle);
        double s = Math.sin(angle);
        double[][] corners = {{length / 2, width / 2}, {-length / 2, width / 2}, {-length / 2, -width / 2}, {length / 2, -width / 2}};
        Path2D.Double path = new Path2D.Double();
        for (int i = 0; i < corners.length; i++) {
            double wx = x + corners[i][0] * c - corners[i][1] * s;
            double wy = y + corners[i][0] * s + corners[i][1] * c;
            if (i == 0) {
                path.moveTo(view.screenX(wx), view.screenY(wy));
            } else {
                path.lineTo(view.screenX(wx), view.screenY(wy));
            }
        }
        path.closePath();
        return path;
    }
}
