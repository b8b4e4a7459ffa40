package io.robomw.cli;

import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.IOException;
import java.io.InputStream;
import java.io.PrintWriter;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Properties;
import java.util.concurrent.Callable;
import java.util.regex.Pattern;

/**
 * {@code mw new agent|program NAME}: writes a Maven project from a template: a pom that imports
 * {@code io.robomw:mw-bom} with the right scopes, an example agent (or program), and a test that
 * runs it against a simulated robot in-process. It builds offline against RoboMW's installed
 * artifacts ({@code mvn install} in the checkout) with the plugin versions RoboMW builds with.
 */
@Command(mixinStandardHelpOptions = true, name = "new", description = {"Write a Maven project: an agent project (mw new agent NAME) or a program (mw new program NAME).",
        "Each has a pom on RoboMW's BOM, an example, and a test against a simulated robot; build it with mvn package",
        "(once, mvn install -DskipTests in the RoboMW checkout puts RoboMW in your local Maven repository)."})
final class NewCommand implements Callable<Integer> {

    /** What can be made. */
    enum Kind {
        agent, program
    }

    private static final String TEMPLATES = "/io/robomw/cli/templates/";
    private static final Pattern NAME = Pattern.compile("[a-z][a-z0-9]*(-[a-z0-9]+)*");
    private static final Pattern PACKAGE = Pattern.compile("[a-z_][a-z0-9_]*(\\.[a-z_][a-z0-9_]*)*");

    @Parameters(index = "0", paramLabel = "agent|program", description = "what to make")
    Kind kind;

    @Parameters(index = "1", paramLabel = "NAME", description = "the project's artifactId and directory, lower case with dashes: my-agents")
    String name;

    @Option(names = "--group", defaultValue = "org.example", description = "the project's groupId (default ${DEFAULT-VALUE})")
    String group;

    @Option(names = "--package", description = "the Java package (default: GROUP.NAME without dashes)")
    String javaPackage;

    @Option(names = "--class", paramLabel = "CLASS", description = "the example's class name (default: from NAME, e.g. MyAgent)")
    String className;

    @Option(names = "--dir", paramLabel = "DIR", defaultValue = ".", description = "where to create the NAME directory (default: here)")
    Path dir;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws IOException {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (!NAME.matcher(name).matches()) {
            err.println("mw new: '" + name + "' is not a project name; use lower case letters, digits and dashes, e.g. my-agents");
            err.flush();
            return Mw.USER_ERROR;
        }
        String pkg = javaPackage != null ? javaPackage : group + "." + name.replace("-", "");
        if (!PACKAGE.matcher(pkg).matches()) {
            err.println("mw new: '" + pkg + "' is not a Java package name; give --package");
            err.flush();
            return Mw.USER_ERROR;
        }
        String cls = className != null ? className : className(name, kind);
        Path project = dir.resolve(name);
        if (Files.exists(project)) {
            err.println("mw new: " + project + " exists already; choose another NAME or --dir");
            err.flush();
            return Mw.USER_ERROR;
        }
        Map<String, String> values = new LinkedHashMap<>(versions());
        values.put("artifactId", name);
        values.put("groupId", group);
        values.put("package", pkg);
        values.put("packagePath", pkg.replace('.', '/'));
        values.put("Class", cls);
        values.put("buildPlugins", fill(resource("build-plugins.xml"), values).stripTrailing());
        List<String> files = resource(kind + "/files.txt").lines().filter(l -> !l.isBlank()).toList();
        for (String file : files) {
            String text = fill(resource(kind + "/" + file), values);
            Path target = project.resolve(fill(file, values));
            Files.createDirectories(target.getParent());
            Files.writeString(target, text, StandardCharsets.UTF_8);
        }
        out.printf("wrote %s: a RoboMW %s project, %s.%s (%d files)%n", project, kind, pkg, cls, files.size());
        out.printf("next: cd %s && mvn package%s%n", project, kind == Kind.agent
                ? " && mw dispatch --key-file cluster.key --jar target/" + name + "-1.0-SNAPSHOT.jar --agent " + pkg + "." + cls + " --clone HOST..."
                : " && mw run --cp target/" + name + "-1.0-SNAPSHOT.jar " + pkg + "." + cls + " ROBOT.yaml");
        out.flush();
        return 0;
    }

    /** @return the class name a project name suggests: my-patrol → MyPatrolAgent (agent) or MyPatrol (program) */
    static String className(String name, Kind kind) {
        StringBuilder b = new StringBuilder();
        for (String part : name.split("-")) {
            b.append(part.substring(0, 1).toUpperCase(Locale.ROOT)).append(part.substring(1));
        }
        if (Character.isDigit(b.charAt(0))) {
            b.insert(0, 'P');
        }
        String c = b.toString();
        return kind == Kind.agent && !c.endsWith("Agent") ? c + "Agent" : c;
    }

    /** @return the versions a generated pom uses, from the build of this mw */
    static Map<String, String> versions() {
        Properties p = new Properties();
        try (InputStream in = NewCommand.class.getResourceAsStream(TEMPLATES + "versions.properties")) {
            if (in == null) {
                throw new IllegalStateException("mw's templates are missing from its class path (versions.properties)");
            }
            p.load(in);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
        Map<String, String> m = new LinkedHashMap<>();
        p.stringPropertyNames().forEach(k -> m.put(k, p.getProperty(k)));
        return m;
    }

    private static String resource(String path) {
        try (InputStream in = NewCommand.class.getResourceAsStream(TEMPLATES + path)) {
            if (in == null) {
                throw new IllegalStateException("mw's template " + path + " is missing from its class path");
            }
            return new String(in.readAllBytes(), StandardCharsets.UTF_8);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Replaces every {{key}}; a key without a value is a bug in the templates. */
    static String fill(String template, Map<String, String> values) {
        StringBuilder b = new StringBuilder();
        int i = 0;
        while (true) {
            int open = template.indexOf("{{", i);
            if (open < 0) {
                return b.append(template, i, template.length()).toString();
            }
            int close = template.indexOf("}}", open);
            String key = template.substring(open + 2, close);
            String value = values.get(key);
            if (value == null) {
                throw new IllegalStateException("template value {{" + key + "}} is not known");
            }
            b.append(template, i, open).append(value);
            i = close + 2;
        }
    }
}
