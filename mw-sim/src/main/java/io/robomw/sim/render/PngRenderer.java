package io.robomw.sim.render;

import io.robomw.sim.SimWorld;
import io.robomw.sim.world.WorldDescription;

import javax.imageio.ImageIO;
import java.awt.Graphics2D;
import java.awt.geom.Rectangle2D;
import java.awt.image.BufferedImage;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * Pictures of a simulated world as PNG files, drawn by {@link WorldPainter} into an off-screen
 * image: works without a display ({@code -Djava.awt.headless=true}). Stateless.
 *
 * <p>May be called while the world runs in real time (it reads only what a viewer may read);
 * call it after the run for the final picture.
 */
public final class PngRenderer {

    private PngRenderer() {
    }

    /**
     * Draws the world as it is now.
     *
     * @param world   the world
     * @param options size and content
     * @return the picture, {@code options.widthPx()} wide and {@link #heightPx} high
     */
    public static BufferedImage render(SimWorld world, RenderOptions options) {
        int width = options.widthPx();
        int height = heightPx(world.description(), options);
        BufferedImage image = new BufferedImage(width, height, BufferedImage.TYPE_INT_RGB);
        Graphics2D g = image.createGraphics();
        try {
            WorldPainter painter = new WorldPainter(options);
            painter.paint(g, world, WorldPainter.fit(world.description(), width, height, options.marginPx()), width, height);
        } finally {
            g.dispose();
        }
        return image;
    }

    /**
     * Draws the world as it is now into a PNG file, replacing it if it exists.
     *
     * @param world   the world
     * @param file    the PNG file; its folder must exist
     * @param options size and content
     * @throws IOException if the file cannot be written
     */
    public static void write(SimWorld world, Path file, RenderOptions options) throws IOException {
        BufferedImage image = render(world, options);
        try (OutputStream out = Files.newOutputStream(file)) {
            if (!ImageIO.write(image, "png", out)) {
                throw new IOException("no PNG writer in this Java runtime; cannot write " + file);
            }
        }
    }

    /**
     * @param world   a world
     * @param options picture options
     * @return the picture's height: as given, or, for {@link RenderOptions#FIT_HEIGHT}, what the
     *         arena's aspect ratio needs at the given width (within the allowed sizes)
     */
    public static int heightPx(WorldDescription world, RenderOptions options) {
        if (options.heightPx() != RenderOptions.FIT_HEIGHT) {
            return options.heightPx();
        }
        Rectangle2D b = WorldPainter.bounds(world);
        double inner = options.widthPx() - 2.0 * options.marginPx();
        long height = Math.round(inner * b.getHeight() / b.getWidth() + 2.0 * options.marginPx());
        return (int) Math.max(RenderOptions.MIN_SIZE_PX, Math.min(RenderOptions.MAX_SIZE_PX, height));
    }
}
