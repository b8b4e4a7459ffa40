package io.robomw.config.robot;

import io.robomw.api.Clock;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.RobotFactory;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.api.spi.SensorChannel;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;

import java.io.IOException;
import java.net.URI;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.ServiceLoader;
import java.util.Set;
import java.util.TreeSet;

/**
 * Opens robots from YAML description files ({@code file:} URIs) for
 * {@link io.robomw.api.Robots#open}: loads and validates the description, finds its platform by
 * the {@code platform:} value, opens it, and starts watching the file for reloads. The platform's
 * owner threads and the file's watcher report to one {@link FailurePolicy}: the program's, if its
 * services carry one.
 */
public final class DescriptionRobotFactory implements RobotFactory {

    @Override
    public String scheme() {
        return "file";
    }

    @Override
    public Robot open(URI location, PlatformServices services) {
        return open(Path.of(location), services, Clock.system(), Cycling.OWN_THREADS);
    }

    /**
     * @param file     the robot's YAML file
     * @param services services for the platform (a {@link FailurePolicy} among them is the one its
     *                 owner threads report to; else a new {@link FailurePolicy#logging()} one)
     * @param clock    the clock of its execution action thread
     * @param cycling  who runs its cycles
     * @return the open robot
     */
    public Robot open(Path file, PlatformServices services, Clock clock, Cycling cycling) {
        FailurePolicy failures = failurePolicy(services);
        PlatformServices withPolicy = services.find(FailurePolicy.class).isPresent() ? services : services.with(FailurePolicy.class, failures);
        ReloadableDescription description = new ReloadableDescription(file, new RobotDescriptionLoader()::load, failures);
        RobotDescription d = description.current();
        RobotPlatform platform;
        try {
            PlatformConfig config = platformConfig(d, withPolicy, clock, cycling);
            PlatformConfig opened = services.find(ConnectionOverride.class).map(o -> o.applyTo(config)).orElse(config);
            PlatformProvider provider = provider(d);
            List<String> problems = provider.check(opened);
            if (!problems.isEmpty()) {
                throw new RobotException(misfit(d, problems));
            }
            platform = provider.open(opened);
        } catch (IOException e) {
            description.close();
            throw new RobotException(d.source() + ": cannot open robot '" + d.name() + "' on platform '" + d.platform() + "': " + e.getMessage(), e);
        } catch (RuntimeException e) {
            description.close();
            throw e;
        }
        ConfiguredRobot robot;
        try {
            robot = ConfiguredRobot.withComponents(description::current, platform, description);
        } catch (RuntimeException e) {
            platform.close();
            description.close();
            throw e;
        }
        try {
            description.watch();
        } catch (IOException e) {
            org.slf4j.LoggerFactory.getLogger(DescriptionRobotFactory.class)
                    .warn("{}: changes will not be reloaded automatically: {}", d.source(), e.toString());
        }
        return robot;
    }

    /**
     * @param d        a description
     * @param services services for the platform (a {@link FailurePolicy} among them is the one its
     *                 owner threads report to; else a new {@link FailurePolicy#logging()} one)
     * @param clock    its clock
     * @param cycling  who runs its cycles
     * @return what its platform is told
     */
    public static PlatformConfig platformConfig(RobotDescription d, PlatformServices services, Clock clock, Cycling cycling) {
        return platformConfig(d, sensorChannels(d), services, clock, cycling);
    }

    /**
     * The same, with its sensors' channels given: a simulation of many robots of one robot file
     * gives them all one list ({@link #sensorChannels} of the file), not a copy a robot.
     *
     * @param d        a description
     * @param channels {@link #sensorChannels}{@code (d)}, or an equal list
     * @param services services for the platform
     * @param clock    its clock
     * @param cycling  who runs its cycles
     * @return what its platform is told
     */
    public static PlatformConfig platformConfig(RobotDescription d, List<SensorChannel> channels, PlatformServices services, Clock clock,
                                                Cycling cycling) {
        return new PlatformConfig(d.name(), d.platform(), d.connection(), d.motors(), channels,
                d.cyclePeriod(), d.watchdogTimeout(), clock, services, cycling, failurePolicy(services));
    }

    /**
     * @param d a description
     * @return its sensors as its platform is told them, in its order
     */
    public static List<SensorChannel> sensorChannels(RobotDescription d) {
        return d.sensors().stream().map(s -> new SensorChannel(s.name(), s.type(), s.port(), s.options())).toList();
    }

    /**
     * @param services a program's services
     * @return the failure policy among them, which every owner thread of the robot reports to (its
     *         platform's and its description's watcher); else a new {@link FailurePolicy#logging()} one
     */
    static FailurePolicy failurePolicy(PlatformServices services) {
        return services.find(FailurePolicy.class).orElseGet(FailurePolicy::logging);
    }

    /**
     * The platforms RoboMW's own artifacts provide, and which artifact has each: named in the
     * error when a robot file's platform has no driver on the class path.
     */
    public static final Map<String, String> KNOWN_PLATFORMS = Map.of(
            "nxt", "io.robomw:mw-platform", "ev3", "io.robomw:mw-platform", "rcx", "io.robomw:mw-platform",
            "ft-intelligent", "io.robomw:mw-platform", "ft-txt", "io.robomw:mw-platform", "aibo", "io.robomw:mw-platform",
            "sim", "io.robomw:mw-sim");

    /**
     * @param d        a description
     * @param problems what its platform's check found
     * @return one message naming the file, the robot, the platform and every problem
     */
    public static String misfit(RobotDescription d, List<String> problems) {
        return d.source() + ": robot '" + d.name() + "' does not fit platform '" + d.platform() + "': " + String.join("; ", problems);
    }

    /**
     * @param d a description
     * @return the provider of its platform
     * @throws RobotException naming the file, the platforms that are available and the artifact that adds the missing one
     */
    public static PlatformProvider provider(RobotDescription d) {
        ServiceLoader<PlatformProvider> loader = ServiceLoader.load(PlatformProvider.class, DescriptionRobotFactory.class.getClassLoader());
        return loader.stream().map(ServiceLoader.Provider::get).filter(p -> p.platformName().equals(d.platform())).findFirst()
                .orElseThrow(() -> new RobotException(d.source() + ": " + noDriver(d.platform(),
                        loader.stream().map(p -> p.get().platformName()).sorted().toList())));
    }

    /**
     * For a file whose other problems keep it from loading ({@code mw describe} reports them all):
     * the problem {@link #provider} would name, from the platform's name alone.
     *
     * @param platform a {@code platform:} value
     * @return what is wrong if no driver for it is on the class path, as {@link #provider} says it; else empty
     */
    public static java.util.Optional<String> missingDriver(String platform) {
        List<String> present = ServiceLoader.load(PlatformProvider.class, DescriptionRobotFactory.class.getClassLoader()).stream()
                .map(p -> p.get().platformName()).sorted().toList();
        return present.contains(platform) ? java.util.Optional.empty() : java.util.Optional.of(noDriver(platform, present));
    }

    /**
     * @param platform a {@code platform:} value without a driver
     * @param present  the platforms whose drivers are on the class path
     * @return what is wrong and how to fix it: the artifact that has the driver, or the spelling meant
     */
    static String noDriver(String platform, List<String> present) {
        String has = "drivers on the class path: " + (present.isEmpty() ? "none" : String.join(", ", present));
        String artifact = KNOWN_PLATFORMS.get(platform);
        if (artifact != null) {
            return "no driver for platform '" + platform + "' on the class path (" + has + "); add " + artifact + ", which has it"
                    + " (the mw distribution has every driver: mw classpath prints its class path)";
        }
        Set<String> names = new TreeSet<>(KNOWN_PLATFORMS.keySet());
        names.addAll(present);
        String near = names.stream().filter(n -> distance(n, platform) <= 2).min(java.util.Comparator.comparingInt(n -> distance(n, platform)))
                .map(n -> "did you mean '" + n + "'? ").orElse("");
        return "unknown platform '" + platform + "'; " + near + "platforms: " + String.join(", ", names) + " (" + has + ")";
    }

    /** @return the Levenshtein distance of two short names */
    private static int distance(String a, String b) {
        int[] prev = new int[b.length() + 1];
        int[] cur = new int[b.length() + 1];
        for (int j = 0; j <= b.length(); j++) {
            prev[j] = j;
        }
        for (int i = 1; i <= a.length(); i++) {
            cur[0] = i;
            for (int j = 1; j <= b.length(); j++) {
                cur[j] = Math.min(Math.min(cur[j - 1] + 1, prev[j] + 1), prev[j - 1] + (a.charAt(i - 1) == b.charAt(j - 1) ? 0 : 1));
            }
            int[] t = prev;
            prev = cur;
            cur = t;
        }
        return prev[b.length()];
    }
}
