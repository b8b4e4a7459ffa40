package io.robomw.config.robot;

import io.robomw.api.Clock;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
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
import java.util.ServiceLoader;
import java.util.stream.Collectors;

/**
 * Opens robots from YAML description files ({@code file:} URIs) for
 * {@link io.robomw.api.Robots#open}: loads and validates the description, finds its platform by
 * the {@code platform:} value, opens it, and starts watching the file for reloads.
 */
public final class DescriptionRobotFactory implements RobotFactory {

    @Override
    public String scheme() {
        return "file";
    }

    @Override
    public Robot open(URI location, PlatformServices services) {
        return open(Path.of(location), services, Clock.system());
    }

    /**
     * @param file     the robot's YAML file
     * @param services services for the platform
     * @param clock    the clock of its execution action thread
     * @return the open robot
     */
    public Robot open(Path file, PlatformServices services, Clock clock) {
        ReloadableDescription description = new ReloadableDescription(file, new RobotDescriptionLoader());
        RobotDescription d = description.current();
        RobotPlatform platform;
        try {
            PlatformConfig config = platformConfig(d, services, clock);
            PlatformConfig opened = services.find(ConnectionOverride.class).map(o -> o.applyTo(config)).orElse(config);
            platform = provider(d).open(opened);
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
     * @param services services for the platform
     * @param clock    its clock
     * @return what its platform is told
     */
    public static PlatformConfig platformConfig(RobotDescription d, PlatformServices services, Clock clock) {
        return new PlatformConfig(d.name(), d.platform(), d.connection(), d.motors(),
                d.sensors().stream().map(s -> new SensorChannel(s.name(), s.type(), s.port(), s.options())).toList(),
                d.cyclePeriod(), d.watchdogTimeout(), clock, services);
    }

    /**
     * @param d a description
     * @return the provider of its platform
     * @throws RobotException naming the file and the platforms that are available
     */
    public static PlatformProvider provider(RobotDescription d) {
        ServiceLoader<PlatformProvider> loader = ServiceLoader.load(PlatformProvider.class, DescriptionRobotFactory.class.getClassLoader());
        return loader.stream().map(ServiceLoader.Provider::get).filter(p -> p.platformName().equals(d.platform())).findFirst()
                .orElseThrow(() -> new RobotException(d.source() + ": no driver for platform '" + d.platform()
                        + "' on the class path; available: " + loader.stream().map(p -> p.get().platformName()).sorted().collect(Collectors.joining(", "))));
    }
}
