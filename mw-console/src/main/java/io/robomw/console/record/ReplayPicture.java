package io.robomw.console.record;

import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import io.robomw.console.observe.WorldMap;
import io.robomw.sim.render.ViewTransform;
import io.robomw.sim.render.WorldPainter;

import javax.imageio.ImageIO;
import java.awt.BasicStroke;
import java.awt.Color;
import java.awt.Font;
import java.awt.Graphics2D;
import java.awt.RenderingHints;
import java.awt.geom.Path2D;
import java.awt.image.BufferedImage;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * Draws what a replay showed into a PNG, as {@code mw sim --png} draws a live run: the arena (with
 * the simulator's own painter), each robot's trajectory in the simulator's colours, and where each
 * ended. Collects true poses where the recording has them, else the robots' odometry.
 */
public final class ReplayPicture implements Observer {

    private final Map<String, List<Observation.RobotPose>> truth = new LinkedHashMap<>();
    private final Map<String, List<Observation.RobotPose>> odometry = new LinkedHashMap<>();
    private WorldMap world;

    @Override
    public synchronized void observe(Observation o) {
        if (o instanceof Observation.World w) {
            world = w.map();
        } else if (o instanceof Observation.RobotPose p) {
            (p.truth() ? truth : odometry).computeIfAbsent(p.robot(), k -> new ArrayList<>()).add(p);
        } else if (o instanceof Observation.Batch b) {
            b.all().forEach(this::observe);
        }
    }

    /**
     * @return each robot's path as drawn, {x, y, heading} in the map's frame: odometry placed from
     *         the robot's start pose on the recorded map (as the live page placed it), true poses as they are
     */
    synchronized Map<String, List<double[]>> paths() {
        Map<String, List<double[]>> paths = new LinkedHashMap<>();
        for (Map<String, List<Observation.RobotPose>> kind : List.of(odometry, truth)) {
            kind.forEach((robot, poses) -> paths.put(robot, poses.stream().map(p -> world == null ? p : world.placed(p))
                    .map(p -> new double[] {p.x(), p.y(), p.heading()}).toList()));
        }
        return paths;
    }

    /**
     * @param file    the PNG
     * @param widthPx its width
     * @throws IOException if it cannot be written
     */
    public synchronized void write(Path file, int widthPx) throws IOException {
        Map<String, List<double[]>> paths = paths();
        double minX;
        double minY;
        double maxX;
        double maxY;
        if (world != null) {
            double m = world.walls() ? world.wallThickness() : 0;
            minX = -m;
            minY = -m;
            maxX = world.width() + m;
            maxY = world.height() + m;
        } else {
            minX = minY = Double.POSITIVE_INFINITY;
            maxX = maxY = Double.NEGATIVE_INFINITY;
            for (List<double[]> path : paths.values()) {
                for (double[] p : path) {
                    minX = Math.min(minX, p[0] - 0.5);
                    minY = Math.min(minY, p[1] - 0.5);
                    maxX = Math.max(maxX, p[0] + 0.5);
                    maxY = Math.max(maxY, p[1] + 0.5);
                }
            }
            if (!Double.isFinite(minX)) {
                minX = minY = -1;
                maxX = maxY = 1;
            }
        }
        int margin = 24;
        int heightPx = (int) Math.max(64, Math.round((widthPx - 2 * margin) * (maxY - minY) / (maxX - minX)) + 2 * margin);
        ViewTransform view = ViewTransform.fit(minX, minY, maxX, maxY, widthPx, heightPx, margin);
        BufferedImage image = new BufferedImage(widthPx, heightPx, BufferedImage.TYPE_INT_RGB);
        Graphics2D g = image.createGraphics();
        try {
            g.setRenderingHint(RenderingHints.KEY_ANTIALIASING, RenderingHints.VALUE_ANTIALIAS_ON);
            g.setColor(Color.WHITE);
            g.fillRect(0, 0, widthPx, heightPx);
            if (world != null) {
                WorldPainter.paintArena(g, world.description(), view);
            }
            int i = 0;
            g.setFont(new Font(Font.SANS_SERIF, Font.PLAIN, 12));
            for (Map.Entry<String, List<double[]>> e : paths.entrySet()) {
                int index = world == null ? i : Math.max(0, indexOf(e.getKey(), i));
                Color c = WorldPainter.robotColor(index);
                Path2D.Double path = new Path2D.Double();
                List<double[]> pts = e.getValue();
                path.moveTo(view.screenX(pts.get(0)[0]), view.screenY(pts.get(0)[1]));
                for (double[] p : pts) {
                    path.lineTo(view.screenX(p[0]), view.screenY(p[1]));
                }
                g.setColor(c);
                g.setStroke(new BasicStroke(2f, BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND));
                g.draw(path);
                double[] end = pts.get(pts.size() - 1);
                int x = (int) view.screenX(end[0]);
                int y = (int) view.screenY(end[1]);
                g.fillOval(x - 5, y - 5, 10, 10);
                g.drawLine(x, y, (int) (x + 12 * Math.cos(end[2])), (int) (y - 12 * Math.sin(end[2])));
                g.setColor(Color.DARK_GRAY);
                g.drawString(e.getKey() + (truth.containsKey(e.getKey()) ? "" : " (odometry)"), x + 8, y - 8);
                i++;
            }
            g.setColor(Color.DARK_GRAY);
            g.drawString("replayed" + (world != null ? ": " + world.name() : ""), margin, heightPx - 6);
        } finally {
            g.dispose();
        }
        Path parent = file.toAbsolutePath().getParent();
        if (parent != null) {
            Files.createDirectories(parent);
        }
        ImageIO.write(image, "png", file.toFile());
    }

    private int indexOf(String robot, int fallback) {
        for (int i = 0; i < world.robots().size(); i++) {
            if (world.robots().get(i).name().equals(robot)) {
                return i;
            }
        }
        return fallback;
    }
}
