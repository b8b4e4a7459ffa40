package io.robomw.agents.host;

import io.robomw.api.Agent;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import javax.tools.JavaCompiler;
import javax.tools.ToolProvider;
import java.io.ByteArrayOutputStream;
import java.io.OutputStream;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.jar.JarEntry;
import java.util.jar.JarOutputStream;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * Agent code compiled here, into jars the host has never seen: it travels with the agent, two
 * versions of one class live on one host at once, and array classes and classes named only by
 * field types resolve.
 */
class CodeShippingTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("code shipping");
    private final List<AutoCloseable> open = new ArrayList<>();

    @TempDir
    Path dir;

    @AfterEach
    void close() throws Exception {
        for (AutoCloseable c : open) {
            c.close();
        }
    }

    private static final String AGENT = """
            package shipped;
            import java.util.*;
            public class VersionedAgent extends io.robomw.api.Agent {
                public record Point(double x, double y) implements java.io.Serializable {}
                public interface Shape extends java.io.Serializable { double area(); }
                public static final class Square implements Shape { final double side; Square(double s) { side = s; } public double area() { return side * side; } }
                private final Point[] corners = { new Point(0, 0), new Point(1, 1) };
                private final Map<String, Point[]> named = new HashMap<>(Map.of("diagonal", corners));
                private final Shape shape = new Square(2);   // referenced only through a field of an interface type
                private int[][] grid = new int[3][4];
                public void run() {
                    context().setResult("VERSION " + corners.length + " " + named.get("diagonal")[1].x() + " " + shape.area() + " " + grid[2].length);
                }
            }
            """;

    private Path compileJar(String version) throws Exception {
        Path src = dir.resolve("src-" + version + "/shipped/VersionedAgent.java");
        Files.createDirectories(src.getParent());
        Files.writeString(src, AGENT.replace("VERSION", version));
        Path classes = dir.resolve("classes-" + version);
        Files.createDirectories(classes);
        JavaCompiler javac = ToolProvider.getSystemJavaCompiler();
        OutputStream quiet = new ByteArrayOutputStream();
        int rc = javac.run(null, quiet, quiet, "--release", "17", "-cp", System.getProperty("java.class.path"), "-d", classes.toString(), src.toString());
        assertEquals(0, rc, quiet.toString());
        Path jar = dir.resolve("agent-" + version + ".jar");
        try (JarOutputStream out = new JarOutputStream(Files.newOutputStream(jar)); Stream<Path> files = Files.walk(classes)) {
            for (Path f : files.filter(Files::isRegularFile).sorted().toList()) {
                out.putNextEntry(new JarEntry(classes.relativize(f).toString().replace('\\', '/')));
                out.write(Files.readAllBytes(f));
                out.closeEntry();
            }
        }
        return jar;
    }

    private Agent load(Path jar) throws Exception {
        URLClassLoader loader = new URLClassLoader(new URL[] {jar.toUri().toURL()}, Agent.class.getClassLoader());
        open.add(loader);
        return (Agent) loader.loadClass("shipped.VersionedAgent").getConstructor().newInstance();
    }

    private AgentHost host(String name) throws Exception {
        AgentHost h = AgentHost.builder(name).clusterKey(KEY).start();
        open.add(0, h);
        return h;
    }

    @Test
    void twoVersionsOfOneAgentClassRunOnOneHostAtOnceWithArraysAndFieldOnlyClasses() throws Exception {
        AgentHost host = host("robot-host");
        AgentHost home = host("home");
        Agent v1 = load(compileJar("v1"));
        Agent v2 = load(compileJar("v2"));
        var r1 = home.agency().sendAgent(host.address(), v1);
        var r2 = home.agency().sendAgent(host.address(), v2);
        assertEquals("v1 2 1.0 4.0 4", r1.result().get(10, TimeUnit.SECONDS));
        assertEquals("v2 2 1.0 4.0 4", r2.result().get(10, TimeUnit.SECONDS));
    }
}
