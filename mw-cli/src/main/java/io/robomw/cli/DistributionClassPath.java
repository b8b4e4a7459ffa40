package io.robomw.cli;

import java.io.File;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.List;

/**
 * The class path of the running {@code mw}: the distribution (mw-cli's jar and
 * {@code mw-cli/target/lib}, every RoboMW module, every driver, the logging binding), as absolute
 * paths. {@code mw classpath} prints it; {@code mw run} starts programs on it.
 */
final class DistributionClassPath {

    private DistributionClassPath() {
    }

    /** @return the entries, absolute, in order (the launcher's {@code lib/*} is expanded by the JVM) */
    static List<String> entries() {
        return Arrays.stream(System.getProperty("java.class.path").split(File.pathSeparator))
                .filter(e -> !e.isBlank())
                .map(e -> Path.of(e).toAbsolutePath().normalize().toString())
                .toList();
    }

    /**
     * @param extra entries to add after the distribution's (a program's own jars)
     * @return the class path, separated as this platform separates them
     */
    static String with(List<String> extra) {
        List<String> all = new java.util.ArrayList<>(entries());
        extra.forEach(e -> all.add(Path.of(e).toAbsolutePath().normalize().toString()));
        return String.join(File.pathSeparator, all);
    }
}
