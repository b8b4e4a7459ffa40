package io.robomw.config.robot;

import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.description.SensorSpec;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.file.ClosedWatchServiceException;
import java.nio.file.FileSystems;
import java.nio.file.Path;
import java.nio.file.StandardWatchEventKinds;
import java.nio.file.WatchKey;
import java.nio.file.WatchService;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.atomic.AtomicReference;
import java.util.function.Consumer;

/**
 * A robot description that can be reloaded while the robot runs. A changed file is validated
 * first; a valid change is swapped in at once for every later command, an invalid one is rejected
 * with its error and the old description stays.
 *
 * <p>What may change at run time: geometry, speeds, conversions, positions, capabilities, actions,
 * the watchdog timeout, a legged drive's templates, limits and gait. What may not, because the
 * platform was opened with it: the name, the platform, the connection, the cycle rate, the drive's
 * type (wheels or legs), the motor ports and the sensors' names, types and ports. Such a change is
 * rejected with a message saying to restart the robot.
 *
 * <p>Thread-safe. {@link #watch()} starts one named daemon thread that reloads when the file
 * changes; {@link #close()} stops it.
 */
public final class ReloadableDescription implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(ReloadableDescription.class);

    private final Path file;
    private final RobotDescriptionLoader loader;
    private final AtomicReference<RobotDescription> current;
    private final List<Consumer<RobotDescription>> listeners = new CopyOnWriteArrayList<>();
    private final AtomicReference<WatchService> watcher = new AtomicReference<>();

    /**
     * Loads the file.
     *
     * @param file   the robot's YAML file
     * @param loader the loader
     * @throws DescriptionException if the file is invalid
     */
    public ReloadableDescription(Path file, RobotDescriptionLoader loader) {
        this.file = file.toAbsolutePath();
        this.loader = loader;
        this.current = new AtomicReference<>(loader.load(this.file));
    }

    /** @return the description in force */
    public RobotDescription current() {
        return current.get();
    }

    /** @return the file */
    public Path file() {
        return file;
    }

    /**
     * @param listener called with each accepted description, on the reloading thread
     */
    public void addListener(Consumer<RobotDescription> listener) {
        listeners.add(listener);
    }

    /**
     * Reads the file again and swaps the description in if it is valid and compatible.
     *
     * @return whether it was accepted, and why not
     */
    public ReloadOutcome reload() {
        RobotDescription next;
        try {
            next = loader.load(file);
        } catch (DescriptionException e) {
            LOG.warn("rejected reload of {}: {}; the previous description stays in force", file, e.getMessage());
            return ReloadOutcome.rejected(e.getMessage());
        }
        RobotDescription previous = current.get();
        String incompatibility = incompatibility(previous, next);
        if (incompatibility != null) {
            String message = file + ": " + incompatibility + " cannot change while the robot runs; restart the robot to apply it";
            LOG.warn("rejected reload: {}; the previous description stays in force", message);
            return ReloadOutcome.rejected(message);
        }
        if (previous.equals(next)) {
            return ReloadOutcome.unchanged();
        }
        current.set(next);
        LOG.info("reloaded {}", file);
        listeners.forEach(l -> l.accept(next));
        return ReloadOutcome.swapped();
    }

    /**
     * Starts watching the file, reloading when it changes. Idempotent.
     *
     * @throws IOException if the file system cannot watch the directory
     */
    public void watch() throws IOException {
        WatchService service = FileSystems.getDefault().newWatchService();
        if (!watcher.compareAndSet(null, service)) {
            service.close();
            return;
        }
        file.getParent().register(service, StandardWatchEventKinds.ENTRY_MODIFY, StandardWatchEventKinds.ENTRY_CREATE);
        Thread thread = new Thread(() -> watchLoop(service), "robomw-reload-" + current().name());
        thread.setDaemon(true);
        thread.start();
    }

    private void watchLoop(WatchService service) {
        try {
            while (true) {
                WatchKey key = service.take();
                boolean ours = key.pollEvents().stream().anyMatch(e -> file.getFileName().equals(e.context()));
                key.reset();
                if (ours) {
                    reload();
                }
            }
        } catch (ClosedWatchServiceException | InterruptedException e) {
            LOG.debug("stopped watching {}", file);
        }
    }

    /** Stops watching. */
    @Override
    public void close() {
        WatchService service = watcher.getAndSet(null);
        if (service != null) {
            try {
                service.close();
            } catch (IOException e) {
                LOG.debug("closing the watch service of {}", file, e);
            }
        }
    }

    private static String incompatibility(RobotDescription a, RobotDescription b) {
        if (!a.name().equals(b.name())) {
            return "the name (" + a.name() + " -> " + b.name() + ")";
        }
        if (!a.platform().equals(b.platform())) {
            return "the platform (" + a.platform() + " -> " + b.platform() + ")";
        }
        if (!a.connection().values().equals(b.connection().values())) {
            return "the connection";
        }
        if (!a.cyclePeriod().equals(b.cyclePeriod())) {
            return "cycle_hz";
        }
        if (a.leggedDrive().isPresent() != b.leggedDrive().isPresent()) {
            return "the drive's type (" + driveType(a) + " -> " + driveType(b) + "), which decided the platform it was opened on";
        }
        if (!a.motorPorts().equals(b.motorPorts())) {
            return "the motor ports (" + a.motorPorts() + " -> " + b.motorPorts() + ")";
        }
        if (!a.motors().equals(b.motors())) {
            return "the wheels' encoder ticks or counters, which its driver reads when it opens";
        }
        if (!a.messaging().equals(b.messaging())) {
            return "the messaging section, which its communication component reads when it starts";
        }
        if (!a.agency().equals(b.agency())) {
            return "the agency section, which its agency reads when it starts";
        }
        if (!Objects.equals(channels(a), channels(b))) {
            return "the sensors' names, types or ports";
        }
        return null;
    }

    private static String driveType(RobotDescription d) {
        return d.leggedDrive().isPresent() ? "legged" : d.drive().isPresent() ? "differential" : "none";
    }

    private static List<String> channels(RobotDescription d) {
        return d.sensors().stream().map(ReloadableDescription::channel).toList();
    }

    private static String channel(SensorSpec s) {
        return s.name() + "/" + s.type() + "/" + s.port();
    }

    /**
     * What a reload did.
     *
     * @param accepted whether the new description is in force
     * @param changed  whether it differs from the old one
     * @param message  why it was rejected, or empty
     */
    public record ReloadOutcome(boolean accepted, boolean changed, String message) {
        static ReloadOutcome swapped() {
            return new ReloadOutcome(true, true, "");
        }

        static ReloadOutcome unchanged() {
            return new ReloadOutcome(true, false, "");
        }

        static ReloadOutcome rejected(String message) {
            return new ReloadOutcome(false, false, message);
        }
    }
}
