package io.robomw.config.yaml;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Optional;

/**
 * Where the files a description file names may lie: its directory tree. A world file names robot
 * files, and a world from someone else must not make RoboMW read (and quote in its error
 * messages) files elsewhere, such as {@code /etc/shadow} or {@code ~/.ssh/id_rsa}. Files the user
 * names on the command line are read wherever they are; only the paths written inside files are
 * held to their file's tree.
 *
 * <p>The tree of a file is the folder above the file's folder (so a project's {@code worlds/} may
 * name files in its {@code robots/}, as RoboMW's {@code examples/} do), or the file's own folder
 * when the one above would be the file system's root, the user's home folder or a folder holding
 * it. A path that leaves the tree (also through a symbolic link) or goes through a hidden folder
 * ({@code .ssh}, {@code .robomw}, ...) is refused.
 *
 * @param root the top of the tree (absolute, normalized)
 */
public record FileScope(Path root) {

    /**
     * @param file a description file
     * @return the tree the paths it names must stay in
     */
    public static FileScope of(Path file) {
        Path dir = file.toAbsolutePath().normalize().getParent();
        Path up = dir.getParent();
        Path home = Path.of(System.getProperty("user.home")).toAbsolutePath().normalize();
        boolean tooHigh = up == null || up.getParent() == null || home.startsWith(up);
        return new FileScope(tooHigh ? dir : up);
    }

    /**
     * @param named a path a file names, resolved against the file's folder
     * @return why it may not be read, or empty if it may
     */
    public Optional<String> refusal(Path named) {
        Path p = named.toAbsolutePath().normalize();
        if (!p.startsWith(root)) {
            return Optional.of(p + " is outside " + root + ", the tree this file may name files in (its folder, or the folder above it"
                    + " unless that is / or your home folder); move the file there");
        }
        for (Path part : root.relativize(p)) {
            if (part.toString().startsWith(".")) {
                return Optional.of(p + " is in a hidden folder (" + part + "), where this file may not name files");
            }
        }
        if (Files.exists(p)) {
            try {
                Path real = p.toRealPath();
                Path realRoot = root.toRealPath();
                if (!real.startsWith(realRoot)) {
                    return Optional.of(p + " leads out of " + root + " (a link to " + real + "), the tree this file may name files in");
                }
            } catch (IOException e) {
                return Optional.of(p + " cannot be resolved: " + e.getMessage());
            }
        }
        return Optional.empty();
    }
}
