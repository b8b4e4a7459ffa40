package io.robomw.api;

import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.RobotFactory;

import java.net.URI;
import java.nio.file.Path;
import java.util.ServiceLoader;

/**
 * Opens robots. The implementations are found at run time ({@link RobotFactory} through
 * {@link ServiceLoader}): {@code mw-config} opens robots from YAML descriptions, {@code mw-agents}
 * opens robots served by another process.
 */
public final class Robots {

    private Robots() {
    }

    /**
     * Opens the robot a YAML description file describes, and connects to its hardware.
     *
     * @param description the robot's YAML file
     * @return the robot; close it when done
     * @throws RobotException if the file is invalid (the message names file, line and column) or the link cannot be opened
     */
    public static Robot open(Path description) {
        return open(description, PlatformServices.none());
    }

    /**
     * Opens a robot from its description, giving its platform extra services (for example the
     * simulated world a {@code platform: sim} robot lives in).
     *
     * @param description the robot's YAML file
     * @param services    services for the platform
     * @return the robot
     */
    public static Robot open(Path description, PlatformServices services) {
        return factory("file").open(description.toUri(), services);
    }

    /**
     * Connects to a robot served by another process, for example
     * {@code Robots.remote("tcp://127.0.0.1:7000/nxt-1")}. Its {@code move}, {@code turn} and
     * {@code getValue} run on the remote robot, with the same errors as local calls.
     *
     * @param address the robot's address; the scheme chooses the transport
     * @return the remote robot
     */
    public static Robot remote(String address) {
        return remote(address, PlatformServices.none());
    }

    /**
     * Connects to a robot served by another process, with settings for the connection (for
     * example TLS keys or the payload allow-list, as the transport's factory documents).
     *
     * @param address  the robot's address; the scheme chooses the transport
     * @param services settings for the connection, looked up by type
     * @return the remote robot; close it when done
     */
    public static Robot remote(String address, PlatformServices services) {
        URI uri = URI.create(address);
        return factory(uri.getScheme()).open(uri, services);
    }

    private static RobotFactory factory(String scheme) {
        ServiceLoader<RobotFactory> loader = ServiceLoader.load(RobotFactory.class, Robots.class.getClassLoader());
        return loader.stream()
                .map(ServiceLoader.Provider::get)
                .filter(f -> f.scheme().equals(scheme))
                .findFirst()
                .orElseThrow(() -> new RobotException(noFactory(scheme, loader.stream().map(p -> p.get().scheme()).toList())));
    }

    /**
     * @param scheme  the address scheme nobody opens
     * @param present the schemes the factories on the class path open
     * @return what is wrong and which artifact fixes it
     */
    static String noFactory(String scheme, java.util.List<String> present) {
        String artifact = "file".equals(scheme) ? "io.robomw:mw-config (robot files) and a driver artifact, io.robomw:mw-platform or io.robomw:mw-sim"
                : "io.robomw:mw-agents (tcp, udp, rmi, multicast and mqtt addresses)";
        return "no robot factory for '" + scheme + "' robots on the class path (found: " + (present.isEmpty() ? "none" : String.join(", ", present))
                + "); add " + artifact + ", or run with the mw distribution's class path (mw run, mw classpath)";
    }
}
