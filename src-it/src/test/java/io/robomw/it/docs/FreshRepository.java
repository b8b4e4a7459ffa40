package io.robomw.it.docs;

import io.robomw.it.demo.MwProcess;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A fresh local Maven repository for a test, with RoboMW in it as {@code mvn install} puts it
 * there: the parent pom, the BOM and the modules built by this build, each installed by the
 * maven-install-plugin ({@code install:install-file}, the jar and pom of each module). What RoboMW
 * does not make (plugins, libraries) is linked, read-only, from the user's repository, since the
 * build is offline; {@code io/robomw} is the fresh repository's own. Nothing is written to the
 * user's repository.
 */
final class FreshRepository {

    /** The modules a generated project uses, in install order. */
    static final List<String> MODULES = List.of("mw-api", "mw-config", "mw-platform", "mw-sim", "mw-agents");
    static final String VERSION = "0.1.0-SNAPSHOT";
    private static final String INSTALL = "org.apache.maven.plugins:maven-install-plugin:3.1.4:install-file";

    private FreshRepository() {
    }

    /** @return the repository, made in {@code dir} */
    static Path create(Path dir) throws IOException, InterruptedException {
        Path shared = Path.of(System.getProperty("it.sharedRepository", Path.of(System.getProperty("user.home"), ".m2", "repository").toString()));
        assertTrue(Files.isDirectory(shared), "the local repository the build used: " + shared);
        Path repo = Files.createDirectories(dir.resolve("repository"));
        try (Stream<Path> top = Files.list(shared)) {
            for (Path entry : top.toList()) {
                String name = entry.getFileName().toString();
                if (name.equals("io")) {
                    Path io = Files.createDirectories(repo.resolve("io"));
                    try (Stream<Path> ios = Files.list(entry)) {
                        for (Path child : ios.filter(c -> !c.getFileName().toString().equals("robomw")).toList()) {
                            Files.createSymbolicLink(io.resolve(child.getFileName().toString()), child);
                        }
                    }
                } else if (Files.isDirectory(entry)) {
                    Files.createSymbolicLink(repo.resolve(name), entry);
                }
            }
        }
        Path checkout = MwProcess.CHECKOUT;
        install(repo, dir, checkout.resolve("pom.xml"), checkout.resolve("pom.xml"), "robomw-parent", "pom");
        install(repo, dir, checkout.resolve("mw-bom/pom.xml"), checkout.resolve("mw-bom/pom.xml"), "mw-bom", "pom");
        for (String m : MODULES) {
            Path jar = checkout.resolve(m).resolve("target").resolve(m + "-" + VERSION + ".jar");
            assertTrue(Files.isRegularFile(jar), "built by this build: " + jar);
            install(repo, dir, jar, checkout.resolve(m).resolve("pom.xml"), m, "jar");
        }
        assertTrue(Files.isRegularFile(repo.resolve("io/robomw/mw-bom/" + VERSION + "/mw-bom-" + VERSION + ".pom")), "the BOM is installed");
        return repo;
    }

    private static void install(Path repo, Path dir, Path file, Path pom, String artifactId, String packaging) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>(List.of("mvn", "-o", "-B", "-q", "-Dmaven.repo.local=" + repo, INSTALL, "-Dfile=" + file, "-DpomFile=" + pom,
                "-DgroupId=io.robomw", "-DartifactId=" + artifactId, "-Dversion=" + VERSION, "-Dpackaging=" + packaging));
        Path log = dir.resolve("install-" + artifactId + ".log");
        Process p = new ProcessBuilder(command).directory(dir.toFile()).redirectErrorStream(true).redirectOutput(log.toFile()).start();
        assertTrue(p.waitFor(180, TimeUnit.SECONDS), "mvn install-file " + artifactId + " within 180 s");
        assertEquals(0, p.exitValue(), "mvn install-file " + artifactId + ": " + Files.readString(log, StandardCharsets.UTF_8));
    }
}
