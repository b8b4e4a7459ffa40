package io.robomw.sim.render;

import io.robomw.sim.SimWorld;
import io.robomw.sim.Simulation;

import javax.swing.AbstractAction;
import javax.swing.ActionMap;
import javax.swing.InputMap;
import javax.swing.JButton;
import javax.swing.JComponent;
import javax.swing.JFrame;
import javax.swing.JLabel;
import javax.swing.JPanel;
import javax.swing.JToolBar;
import javax.swing.KeyStroke;
import javax.swing.SwingUtilities;
import javax.swing.Timer;
import javax.swing.WindowConstants;
import java.awt.BorderLayout;
import java.awt.Dimension;
import java.awt.Graphics;
import java.awt.Graphics2D;
import java.awt.GraphicsEnvironment;
import java.awt.HeadlessException;
import java.awt.Point;
import java.awt.event.ActionEvent;
import java.awt.event.KeyEvent;
import java.awt.event.MouseAdapter;
import java.awt.event.MouseEvent;
import java.awt.event.MouseWheelEvent;
import java.awt.event.WindowAdapter;
import java.awt.event.WindowEvent;
import java.lang.reflect.InvocationTargetException;
import java.util.Locale;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A window that shows a simulation running in real time, drawn by {@link WorldPainter} (the same
 * picture as the PNG renderer) about {@value #FRAMES_PER_SECOND} times a second.
 *
 * <p>Controls: drag to pan, mouse wheel to zoom about the pointer, <b>space</b> (or the button)
 * to pause and resume, <b>+</b> / <b>-</b> (or the buttons) to double or halve the speed,
 * <b>F</b> or <b>Home</b> to fit the arena again, <b>R</b> to show or hide sensor rays. Closing
 * the window stops the real-time run for good.
 *
 * <p>Threads: the window lives on the Swing event thread and paints from it while the simulation's
 * own thread steps the world; it reads only what may be read during a step (poses, trajectories,
 * range readings, time). {@link #open} and {@link #close} may be called from any thread.
 */
public final class SimViewer {

    /** Repaints per second. */
    public static final int FRAMES_PER_SECOND = 30;
    private static final double WHEEL_ZOOM = 1.15;
    private static final int FIRST_WIDTH_PX = 1000;
    private static final int FIRST_HEIGHT_PX = 760;

    private final SimWorld world;
    private final RealTimeControl control;
    private final CountDownLatch closed = new CountDownLatch(1);
    private JFrame frame;
    private ViewPanel panel;
    private JLabel status;
    private JButton pauseButton;
    private Timer timer;

    private SimViewer(Simulation simulation, RealTimeControl control) {
        this.world = simulation.world();
        this.control = control;
    }

    /**
     * Opens a window on a simulation and starts its real-time run; returns once the window shows.
     *
     * @param simulation the simulation, not yet running in real time
     * @param options    what to draw (its sizes are ignored: the window has its own)
     * @param speed      the first speed, simulated seconds per wall-clock second
     * @return the viewer
     * @throws HeadlessException if there is no display ({@link GraphicsEnvironment#isHeadless()})
     */
    public static SimViewer open(Simulation simulation, RenderOptions options, double speed) {
        if (GraphicsEnvironment.isHeadless()) {
            throw new HeadlessException("no display: the simulation viewer needs a desktop (or Xvfb); write a picture with a PNG instead");
        }
        SimViewer viewer = new SimViewer(simulation, new RealTimeControl(simulation, speed));
        onEventThread(() -> viewer.build(simulation, options));
        viewer.control.resume();
        return viewer;
    }

    private static void onEventThread(Runnable r) {
        if (SwingUtilities.isEventDispatchThread()) {
            r.run();
            return;
        }
        try {
            SwingUtilities.invokeAndWait(r);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException("interrupted while opening the simulation viewer", e);
        } catch (InvocationTargetException e) {
            throw new IllegalStateException("cannot open the simulation viewer: " + e.getCause(), e.getCause());
        }
    }

    private void build(Simulation simulation, RenderOptions options) {
        frame = new JFrame("RoboMW sim: " + world.description().name());
        frame.setDefaultCloseOperation(WindowConstants.DISPOSE_ON_CLOSE);
        panel = new ViewPanel(world, new WorldPainter(options));
        panel.setPreferredSize(new Dimension(FIRST_WIDTH_PX, FIRST_HEIGHT_PX));
        status = new JLabel();
        pauseButton = button("Pause", "Pause or resume (space)", control::togglePause);
        JToolBar bar = new JToolBar();
        bar.setFloatable(false);
        bar.add(pauseButton);
        bar.add(button("Slower", "Halve the speed (-)", control::slower));
        bar.add(button("Faster", "Double the speed (+)", control::faster));
        bar.add(button("Fit", "Show the whole arena (F)", panel::fit));
        bar.add(button("Rays", "Show or hide sensor rays (R)", panel::toggleRays));
        bar.addSeparator();
        bar.add(status);
        frame.getContentPane().add(bar, BorderLayout.NORTH);
        frame.getContentPane().add(panel, BorderLayout.CENTER);
        bindKeys(frame.getRootPane());
        timer = new Timer(1000 / FRAMES_PER_SECOND, e -> refresh());
        frame.addWindowListener(new WindowAdapter() {
            @Override
            public void windowClosed(WindowEvent e) {
                timer.stop();
                control.stop();
                closed.countDown();
            }
        });
        frame.pack();
        frame.setLocationByPlatform(true);
        frame.setVisible(true);
        timer.start();
        refresh();
    }

    private JButton button(String text, String tip, Runnable action) {
        JButton b = new JButton(text);
        b.setToolTipText(tip);
        // The keys are bound to the window; a focused button would take the space bar for itself.
        b.setFocusable(false);
        b.addActionListener(e -> {
            action.run();
            refresh();
        });
        return b;
    }

    private void bindKeys(JComponent root) {
        InputMap keys = root.getInputMap(JComponent.WHEN_IN_FOCUSED_WINDOW);
        ActionMap actions = root.getActionMap();
        bind(keys, actions, "pause", control::togglePause, KeyStroke.getKeyStroke(KeyEvent.VK_SPACE, 0));
        // Typed characters, so the main keyboard and the keypad both work, and each press counts once.
        bind(keys, actions, "faster", control::faster, KeyStroke.getKeyStroke('+'), KeyStroke.getKeyStroke('='));
        bind(keys, actions, "slower", control::slower, KeyStroke.getKeyStroke('-'));
        bind(keys, actions, "fit", panel::fit, KeyStroke.getKeyStroke(KeyEvent.VK_F, 0), KeyStroke.getKeyStroke(KeyEvent.VK_HOME, 0));
        bind(keys, actions, "rays", panel::toggleRays, KeyStroke.getKeyStroke(KeyEvent.VK_R, 0));
    }

    private void bind(InputMap keys, ActionMap actions, String name, Runnable action, KeyStroke... strokes) {
        for (KeyStroke k : strokes) {
            keys.put(k, name);
        }
        actions.put(name, new AbstractAction(name) {
            @Override
            public void actionPerformed(ActionEvent e) {
                action.run();
                refresh();
            }
        });
    }

    /** Repaints the world and the status line; on the event thread. */
    private void refresh() {
        boolean running = control.isRunning();
        pauseButton.setText(running ? "Pause" : "Resume");
        status.setText(String.format(Locale.ROOT, "  t = %.1f s   speed %s   %s   (drag: pan, wheel: zoom)",
                world.time(), RealTimeControl.format(control.speed()), running ? "running" : "paused"));
        panel.repaint();
    }

    /** @return the pause and speed control the window's buttons use */
    public RealTimeControl control() {
        return control;
    }

    /**
     * Waits until the window is closed (by the user or {@link #close()}).
     *
     * @throws InterruptedException if interrupted while waiting
     */
    public void awaitClosed() throws InterruptedException {
        closed.await();
    }

    /**
     * Waits until the window is closed, at most a while.
     *
     * @param timeout how long
     * @param unit    its unit
     * @return whether it closed
     * @throws InterruptedException if interrupted while waiting
     */
    public boolean awaitClosed(long timeout, TimeUnit unit) throws InterruptedException {
        return closed.await(timeout, unit);
    }

    /** Closes the window, which stops the real-time run; returns at once. */
    public void close() {
        SwingUtilities.invokeLater(() -> frame.dispose());
    }

    /**
     * The drawing area: holds the view transform (touched only on the event thread) and turns
     * mouse drags and wheel turns into pans and zooms.
     */
    private static final class ViewPanel extends JPanel {

        private final SimWorld world;
        private WorldPainter painter;
        private ViewTransform view;
        /** Whether the user panned or zoomed; until then the arena is fitted again when the window resizes. */
        private boolean userMoved;
        private Point dragFrom;

        ViewPanel(SimWorld world, WorldPainter painter) {
            this.world = world;
            this.painter = painter;
            MouseAdapter mouse = new MouseAdapter() {
                @Override
                public void mousePressed(MouseEvent e) {
                    dragFrom = e.getPoint();
                }

                @Override
                public void mouseDragged(MouseEvent e) {
                    if (dragFrom != null && view != null) {
                        view = view.panned(e.getX() - dragFrom.x, e.getY() - dragFrom.y);
                        userMoved = true;
                        dragFrom = e.getPoint();
                        repaint();
                    }
                }

                @Override
                public void mouseReleased(MouseEvent e) {
                    dragFrom = null;
                }

                @Override
                public void mouseWheelMoved(MouseWheelEvent e) {
                    if (view != null) {
                        view = view.zoomedAbout(e.getX(), e.getY(), Math.pow(WHEEL_ZOOM, -e.getPreciseWheelRotation()));
                        userMoved = true;
                        repaint();
                    }
                }
            };
            addMouseListener(mouse);
            addMouseMotionListener(mouse);
            addMouseWheelListener(mouse);
        }

        void fit() {
            userMoved = false;
            view = null;
            repaint();
        }

        void toggleRays() {
            painter = new WorldPainter(painter.options().withRays(!painter.options().showRays()));
            repaint();
        }

        @Override
        protected void paintComponent(Graphics g) {
            super.paintComponent(g);
            int w = getWidth();
            int h = getHeight();
            if (w < 2 || h < 2) {
                return;
            }
            int margin = Math.min(painter.options().marginPx(), Math.min(w, h) / 4);
            if (view == null || !userMoved) {
                view = WorldPainter.fit(world.description(), w, h, margin);
            }
            Graphics2D g2 = (Graphics2D) g.create();
            try {
                painter.paint(g2, world, view, w, h);
            } finally {
                g2.dispose();
            }
        }
    }
}
