package io.robomw.config.robot;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DriveKind;
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
import java.util.concurrent.locks.LockSupport;
import java.util.function.Consumer;

/**
 * A robot description that can be reloaded while the robot runs. A changed file is validated
 * first; a valid change is swapped in at once for every later command, an invalid one is rejected
 * with its error and the old description stays.
 *
 * <p>What may change at run time: geometry, speeds, conversions, positions, capabilities, actions,
 * the watchdog timeout, a legged drive's templates, limits and gait. What may not, because the
 * platform was opened with it: the name, the platform, the connection, the cycle rate, the drive's
 * kind (wheels or legs), the motor ports and the sensors' names, types and ports. Such a change is
 * rejected with a message saying to restart the robot.
 *
 * <h2>The watcher</h2>
 * {@link #watch()} starts one owner thread, {@code robomw-reload-NAME}, on an
 * {@link OwnerThread} with the injected {@link FailurePolicy}: it waits for the file's directory to
 * change and reloads. Whatever one reload throws that is not a file's problem (an unchecked
 * exception from the loader) is reported to the policy and the watch goes on; so is a listener's
 * exception, which neither stops the other listeners nor the watch. {@link #close()} stops it.
 *
 * <p>Thread-safe.
 */
public final class ReloadableDescription implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(ReloadableDescription.class);
    /** How long the watcher waits before looking again when it has nothing to wait on (while it closes). */
    private static final long IDLE_NANOS = 100_000_000L;

    /** Reads a robot file: {@link RobotDescriptionLoader#load}, or a test's stand-in. */
    @FunctionalInterface
    public interface Loader {
        /**
         * @param file a robot file
         * @return its description
         * @throws DescriptionException listing the file's problems
         */
        RobotDescription load(Path file);
    }

    private final Path file;
    private final Loader loader;
    private final FailurePolicy failures;
    private final AtomicReference<RobotDescription> current;
    private final List<Consumer<RobotDescription>> listeners = new CopyOnWriteArrayList<>();
    private final Object watching = new Object();
    private WatchService service;
    private OwnerThread watcher;
    private boolean closed;

    /**
     * Loads the file; a watcher reports to a new {@link FailurePolicy#logging()} policy.
     *
     * @param file   the robot's YAML file
     * @param loader the loader
     * @throws DescriptionException if the file is invalid
     */
    public ReloadableDescription(Path file, RobotDescriptionLoader loader) {
        this(file, loader::load, FailurePolicy.logging());
    }

    /**
     * Loads the file.
     *
     * @param file     the robot's YAML file
     * @param loader   what reads it
     * @param failures where the watcher reports what it catches (the robot's one policy)
     * @throws DescriptionException if the file is invalid
     */
    public ReloadableDescription(Path file, Loader loader, FailurePolicy failures) {
        this.file = file.toAbsolutePath();
        this.loader = Objects.requireNonNull(loader, "loader");
        this.failures = Objects.requireNonNull(failures, "failures");
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
     * @param listener called with each accepted description, on the reloading thread; what it
     *                 throws is reported to the failure policy
     */
    public void addListener(Consumer<RobotDescription> listener) {
        listeners.add(listener);
    }

    /**
     * Reads the file again and swaps the description in if it is valid and compatible, then tells
     * the listeners.
     *
     * @return whether it was swapped in, unchanged or rejected, and why
     * @throws RuntimeException what the loader throws other than a {@link DescriptionException}
     *                          (on the watcher, reported to the failure policy)
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
            return ReloadOutcome.UNCHANGED;
        }
        current.set(next);
        LOG.info("reloaded {}", file);
        for (Consumer<RobotDescription> listener : listeners) {
            try {
                listener.accept(next);
            } catch (Throwable t) {
                failures.surviveOrRethrow(role(), t);
            }
        }
        return ReloadOutcome.SWAPPED;
    }

    /**
     * Starts watching the file, reloading when it changes. Idempotent; does nothing once closed.
     *
     * @throws IOException if the file system cannot watch the directory
     */
    public void watch() throws IOException {
        synchronized (watching) {
            if (watcher != null || closed) {
                return;
            }
            WatchService s = FileSystems.getDefault().newWatchService();
            try {
                file.getParent().register(s, StandardWatchEventKinds.ENTRY_MODIFY, StandardWatchEventKinds.ENTRY_CREATE);
            } catch (IOException | RuntimeException e) {
                s.close();
                throw e;
            }
            service = s;
            watcher = OwnerThread.start(role(), Thread.NORM_PRIORITY, () -> watchOnce(s), ReloadableDescription::idle, failures);
        }
    }

    /** @return the watcher's name, which failures are reported under */
    private String role() {
        return "robomw-reload-" + current.get().name();
    }

    /**
     * One round of the watcher: waits for the directory to change and reloads if the file did.
     *
     * @return 1 after an event, 0 when the watch service was closed (the watcher is closing)
     */
    private int watchOnce(WatchService s) throws InterruptedException {
        WatchKey key;
        try {
            key = s.take();
        } catch (ClosedWatchServiceException e) {
            return 0;
        }
        boolean ours = key.pollEvents().stream().anyMatch(e -> file.getFileName().equals(e.context()));
        if (!key.reset()) {
            LOG.warn("{}: its directory can no longer be watched; changes will not be reloaded", file);
        }
        if (ours) {
            reload();
        }
        return 1;
    }

    /** The watcher's wait after a round: none after an event (the next wait is the watch's), a short one while it closes. */
    private static void idle(int work) {
        if (work == 0) {
            LockSupport.parkNanos(IDLE_NANOS);
        }
    }

    /** Stops watching: closes the watch service, then ends the watcher and waits for it. Idempotent. */
    @Override
    public void close() {
        WatchService s;
        OwnerThread w;
        synchronized (watching) {
            closed = true;
            s = service;
            w = watcher;
            service = null;
        }
        if (s != null) {
            try {
                s.close();
            } catch (IOException e) {
                LOG.debug("closing the watch service of {}", file, e);
            }
        }
        if (w != null) {
            w.close();
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
        if (!a.driveKind().equals(b.driveKind())) {
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
        return d.driveKind().map(DriveKind::yamlName).orElse("none");
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
     * @param result  whether the new description was swapped in, was the same, or was rejected
     * @param message why it was rejected, or empty
     */
    public record ReloadOutcome(Result result, String message) {

        /** What a reload did with the file it read. */
        public enum Result {
            /** The file was valid and compatible, and differs: it is in force. */
            SWAPPED,
            /** The file was valid and compatible, and the same as the description in force. */
            UNCHANGED,
            /** The file was invalid or changed what may not change: the previous description stays. */
            REJECTED
        }

        /** A reload that swapped the description in. */
        public static final ReloadOutcome SWAPPED = new ReloadOutcome(Result.SWAPPED, "");
        /** A reload that found the description unchanged. */
        public static final ReloadOutcome UNCHANGED = new ReloadOutcome(Result.UNCHANGED, "");

        /** Checks the values. */
        public ReloadOutcome {
            Objects.requireNonNull(result, "result");
            Objects.requireNonNull(message, "message");
        }

        /**
         * @param message why
         * @return a rejected reload
         */
        static ReloadOutcome rejected(String message) {
            return new ReloadOutcome(Result.REJECTED, message);
        }

        /** @return whether the file's description is in force (swapped in or unchanged) */
        public boolean accepted() {
            return result != Result.REJECTED;
        }
    }
}
