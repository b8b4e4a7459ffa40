package io.robomw.agents.host.code;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.URISyntaxException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.CodeSource;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.stream.Stream;
import java.util.zip.ZipEntry;
import java.util.zip.ZipOutputStream;

/**
 * Finds the archive to ship with an agent: the archive its class came from (an agent passing
 * through a host), or the jar or class directory its class was loaded from (an agent sent from
 * the process that has its code). A directory becomes a jar with entries in a fixed order and
 * fixed times, so the same classes always give the same digest. Archives are made once per code
 * location and kept. Thread-safe.
 */
public final class CodeSources {

    private final Map<Path, CodeArchive> packed = new ConcurrentHashMap<>();

    /**
     * @param agentClass the agent's class
     * @return the archive holding its code
     * @throws IllegalArgumentException if the class has no code location to ship (a JDK class, or a class made at run time)
     */
    public CodeArchive archiveOf(Class<?> agentClass) {
        if (agentClass.getClassLoader() instanceof ArchiveClassLoader archived) {
            return archived.archive();
        }
        CodeSource source = agentClass.getProtectionDomain().getCodeSource();
        if (source == null || source.getLocation() == null) {
            throw new IllegalArgumentException("agent class " + agentClass.getName() + " has no code location to ship (it was not loaded from a jar or a class directory)");
        }
        Path location;
        try {
            location = Path.of(source.getLocation().toURI());
        } catch (URISyntaxException | IllegalArgumentException e) {
            throw new IllegalArgumentException("agent class " + agentClass.getName() + " comes from " + source.getLocation() + ", which is not a local file", e);
        }
        return packed.computeIfAbsent(location, CodeSources::pack);
    }

    private static CodeArchive pack(Path location) {
        try {
            if (Files.isRegularFile(location)) {
                return CodeArchive.of(Files.readAllBytes(location));
            }
            return CodeArchive.of(zipClasses(location));
        } catch (IOException e) {
            throw new UncheckedIOException("cannot read agent code at " + location + ": " + e.getMessage(), e);
        }
    }

    private static byte[] zipClasses(Path root) throws IOException {
        List<Path> files;
        try (Stream<Path> walk = Files.walk(root)) {
            files = walk.filter(Files::isRegularFile).filter(p -> p.toString().endsWith(".class")).sorted().toList();
        }
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        try (ZipOutputStream zip = new ZipOutputStream(bytes)) {
            for (Path f : files) {
                ZipEntry e = new ZipEntry(root.relativize(f).toString().replace('\\', '/'));
                e.setTime(0L);
                zip.putNextEntry(e);
                zip.write(Files.readAllBytes(f));
                zip.closeEntry();
            }
        }
        return bytes.toByteArray();
    }
}
