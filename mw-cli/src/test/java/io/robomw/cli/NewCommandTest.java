package io.robomw.cli;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.w3c.dom.Document;
import org.w3c.dom.Element;
import org.w3c.dom.NodeList;

import javax.xml.parsers.DocumentBuilderFactory;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw new}: what it writes (every placeholder filled, poms that parse, the scopes), and that
 * its versions are the build's (src-it's FirstAgentProjectDocIT builds what it writes with Maven).
 */
class NewCommandTest {

    @TempDir
    Path dir;

    private static Document xml(Path file) throws Exception {
        return DocumentBuilderFactory.newInstance().newDocumentBuilder().parse(file.toFile());
    }

    /** @return artifactId to scope of a pom's dependencies (compile when none is given) */
    private static Map<String, String> scopes(Document pom) {
        Map<String, String> scopes = new HashMap<>();
        Element deps = (Element) pom.getElementsByTagName("dependencies").item(pom.getElementsByTagName("dependencies").getLength() - 1);
        NodeList list = deps.getElementsByTagName("dependency");
        for (int i = 0; i < list.getLength(); i++) {
            Element d = (Element) list.item(i);
            NodeList scope = d.getElementsByTagName("scope");
            scopes.put(d.getElementsByTagName("artifactId").item(0).getTextContent(), scope.getLength() == 0 ? "compile" : scope.item(0).getTextContent());
        }
        return scopes;
    }

    @Test
    void anAgentProjectWithTheRightScopes() throws Exception {
        CliRun run = CliRun.mw("new", "agent", "my-patrol", "--dir", dir.toString());
        assertEquals(0, run.status(), run.err());
        Path project = dir.resolve("my-patrol");
        assertTrue(run.out().contains("org.example.mypatrol.MyPatrolAgent"), run.out());
        Path agent = project.resolve("src/main/java/org/example/mypatrol/MyPatrolAgent.java");
        assertTrue(Files.readString(agent).contains("public class MyPatrolAgent extends Agent"));
        assertTrue(Files.exists(project.resolve("src/test/java/org/example/mypatrol/MyPatrolAgentTest.java")));
        try (Stream<Path> files = Files.walk(project)) {
            for (Path f : files.filter(Files::isRegularFile).toList()) {
                assertFalse(Files.readString(f).contains("{{"), f + " has an unfilled placeholder");
            }
        }
        Document pom = xml(project.resolve("pom.xml"));
        Map<String, String> scopes = scopes(pom);
        assertEquals("provided", scopes.get("mw-api"), "the agent's jar holds its own classes only");
        assertEquals("test", scopes.get("mw-agents"));
        assertEquals("test", scopes.get("mw-sim"));
        assertTrue(Files.readString(project.resolve("pom.xml")).contains("<artifactId>mw-bom</artifactId><version>${robomw.version}</version><type>pom</type><scope>import</scope>"));

        CliRun again = CliRun.mw("new", "agent", "my-patrol", "--dir", dir.toString());
        assertEquals(2, again.status());
        assertTrue(again.err().contains("exists already"), again.err());
        assertEquals(2, CliRun.mw("new", "agent", "My_Patrol", "--dir", dir.toString()).status());
    }

    @Test
    void aProgramProjectFindsTheLayersAtRunTime() throws Exception {
        CliRun run = CliRun.mw("new", "program", "square", "--dir", dir.toString(), "--group", "com.acme");
        assertEquals(0, run.status(), run.err());
        Map<String, String> scopes = scopes(xml(dir.resolve("square/pom.xml")));
        assertEquals("compile", scopes.get("mw-api"));
        for (String runtime : List.of("mw-config", "mw-platform", "mw-agents", "slf4j-simple")) {
            assertEquals("runtime", scopes.get(runtime), runtime);
        }
        assertTrue(Files.exists(dir.resolve("square/src/main/java/com/acme/square/Square.java")));
    }

    @Test
    void theTemplatesUseTheVersionsRoboMwBuildsWith() throws Exception {
        Map<String, String> v = NewCommand.versions();
        Document parent = xml(Path.of("../pom.xml"));
        assertEquals(parent.getElementsByTagName("version").item(0).getTextContent(), v.get("robomwVersion"));
        NodeList plugins = parent.getElementsByTagName("plugin");
        Map<String, String> pinned = new HashMap<>();
        for (int i = 0; i < plugins.getLength(); i++) {
            Element p = (Element) plugins.item(i);
            NodeList version = p.getElementsByTagName("version");
            if (version.getLength() > 0) {
                pinned.put(p.getElementsByTagName("artifactId").item(0).getTextContent(), version.item(0).getTextContent());
            }
        }
        assertEquals(pinned.get("maven-compiler-plugin"), v.get("compilerPluginVersion"));
        assertEquals(pinned.get("maven-jar-plugin"), v.get("jarPluginVersion"));
        assertEquals(pinned.get("maven-resources-plugin"), v.get("resourcesPluginVersion"));
        assertEquals(pinned.get("maven-install-plugin"), v.get("installPluginVersion"));
        assertEquals(pinned.get("maven-clean-plugin"), v.get("cleanPluginVersion"));
        assertFalse(v.get("junitVersion").contains("$"), "filtered at build time: " + v);

        Document bom = xml(Path.of("../mw-bom/pom.xml"));
        assertEquals(v.get("robomwVersion"), bom.getElementsByTagName("version").item(0).getTextContent(), "the BOM's own version");
        String bomText = Files.readString(Path.of("../mw-bom/pom.xml"));
        for (String module : List.of("mw-api", "mw-config", "mw-platform", "mw-sim", "mw-agents", "mw-console", "mw-cli")) {
            assertTrue(bomText.contains("<artifactId>" + module + "</artifactId><version>${robomw.version}</version>"), "the BOM manages " + module);
        }
        assertTrue(bomText.contains("<robomw.version>" + v.get("robomwVersion") + "</robomw.version>"));
    }
}
