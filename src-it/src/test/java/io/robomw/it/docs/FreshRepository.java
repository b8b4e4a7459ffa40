package io.robomw.it.docs;

import io.robomw.it.demo.MwProcess;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
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
        StringBuilder executions = new StringBuilder();
        execution(executions, "robomw-parent", "pom", checkout.resolve("pom.xml"), checkout.resolve("pom.xml"));
        execution(executions, "mw-bom", "pom", checkout.resolve("mw-bom/pom.xml"), checkout.resolve("mw-bom/pom.xml"));
        for (String m : MODULES) {
            Path jar = checkout.resolve(m).resolve("target").resolve(m + "-" + VERSION + ".jar");
            assertTrue(Files.isRegularFile(jar), "built by this build: " + jar);
            execution(executions, m, "jar", jar, checkout.resolve(m).resolve("pom.xml"));
        }
        // One Maven run: a pom whose build installs each artifact (install:install-file, as mvn install would).
        Path installer = Files.createDirectories(dir.resolve("installer"));
        Files.writeString(installer.resolve("pom.xml"), """
                <project xmlns="http://maven.apache.org/POM/4.0.0">
                  <modelVersion>4.0.0</modelVersion>
                  <groupId>io.robomw.it</groupId><artifactId>installer</artifactId><version>1</version><packaging>pom</packaging>
                  <build><plugins><plugin>
                    <groupId>org.apache.maven.plugins</groupId><artifactId>maven-install-plugin</artifactId><version>3.1.4</version>
                    <executions>
                """ + executions + """
                    </executions>
                  </plugin></plugins></build>
                </project>
                """);
        Path log = dir.resolve("install.log");
        Process p = DocCommands.quickJvm(new ProcessBuilder("mvn", "-o", "-B", "-q", "-Dmaven.repo.local=" + repo, "validate")).directory(installer.toFile())
                .redirectErrorStream(true).redirectOutput(log.toFile()).start();
        assertTrue(p.waitFor(300, TimeUnit.SECONDS), "mvn install-file within 300 s");
        assertEquals(0, p.exitValue(), "installing RoboMW into " + repo + ": " + Files.readString(log, StandardCharsets.UTF_8));
        assertTrue(Files.isRegularFile(repo.resolve("io/robomw/mw-bom/" + VERSION + "/mw-bom-" + VERSION + ".pom")), "the BOM is installed");
        return repo;
    }

    private static void execution(StringBuilder b, String artifactId, String packaging, Path file, Path pom) {
        b.append("      <execution><id>").append(artifactId).append("</id><phase>validate</phase><goals><goal>install-file</goal></goals><configuration>")
                .append("<file>").append(file).append("</file><pomFile>").append(pom).append("</pomFile>")
                .append("<groupId>io.robomw</groupId><artifactId>").append(artifactId).append("</artifactId><version>").append(VERSION)
                .append("</version><packaging>").append(packaging).append("</packaging></configuration></execution>\n");
    }
}
