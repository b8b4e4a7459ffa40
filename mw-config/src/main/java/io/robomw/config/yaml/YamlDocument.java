package io.robomw.config.yaml;

import org.yaml.snakeyaml.LoaderOptions;
import org.yaml.snakeyaml.Yaml;
import org.yaml.snakeyaml.error.Mark;
import org.yaml.snakeyaml.error.MarkedYAMLException;
import org.yaml.snakeyaml.error.YAMLException;
import org.yaml.snakeyaml.events.AliasEvent;
import org.yaml.snakeyaml.events.CollectionEndEvent;
import org.yaml.snakeyaml.events.CollectionStartEvent;
import org.yaml.snakeyaml.events.Event;
import org.yaml.snakeyaml.events.ScalarEvent;
import org.yaml.snakeyaml.nodes.MappingNode;
import org.yaml.snakeyaml.nodes.Node;
import org.yaml.snakeyaml.nodes.NodeTuple;
import org.yaml.snakeyaml.nodes.ScalarNode;
import org.yaml.snakeyaml.nodes.SequenceNode;

import java.io.IOException;
import java.io.InputStream;
import java.io.StringReader;
import java.nio.ByteBuffer;
import java.nio.CharBuffer;
import java.nio.charset.CharsetDecoder;
import java.nio.charset.CoderResult;
import java.nio.charset.CodingErrorAction;
import java.nio.charset.StandardCharsets;
import java.nio.file.AccessDeniedException;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.ArrayDeque;
import java.util.Deque;
import java.util.HashMap;
import java.util.HashSet;
import java.util.IdentityHashMap;
import java.util.Map;
import java.util.Set;

/**
 * Parses a YAML file into SnakeYAML's node tree, which keeps the line and column of every value,
 * and hands out a {@link MappingReader} on its top-level mapping. Whatever the file holds, reading
 * it ends in a reader or in a {@link io.robomw.config.description.DescriptionException} naming the
 * file, line and column; never in another exception, and never after reading or building more
 * than the limits below allow:
 *
 * <ul>
 * <li>a regular file only: a FIFO, a device ({@code /dev/zero}) or a socket is refused before it is
 *     opened (opening a FIFO without a writer would wait forever);</li>
 * <li>at most {@value #MAX_FILE_BYTES} bytes (1 MiB), checked while reading, so a huge file is
 *     refused after 1 MiB, not read to the end;</li>
 * <li>UTF-8 text only: another encoding is refused at the first byte that is not UTF-8;</li>
 * <li>at most {@value #MAX_DEPTH} levels of nested lists and mappings;</li>
 * <li>aliases: at most {@value #MAX_COLLECTION_ALIASES} to lists or mappings, none to a value it is
 *     inside (a value cannot contain itself), and the file may not expand through its aliases to
 *     more than {@value #MAX_VALUES} values (an alias bomb is refused before it is expanded);</li>
 * <li>no key twice in one mapping, anywhere in the file; keys are plain names;</li>
 * <li>no custom tags: nothing is constructed but plain data.</li>
 * </ul>
 */
public final class YamlDocument {

    /** The largest file read, in bytes. */
    public static final int MAX_FILE_BYTES = 1 << 20;
    /** The deepest nesting of lists and mappings. */
    public static final int MAX_DEPTH = 40;
    /** The most aliases to lists or mappings in one file. */
    public static final int MAX_COLLECTION_ALIASES = 50;
    /** The most values (scalars, lists and mappings) a file may expand to through its aliases. */
    public static final int MAX_VALUES = Problems.MAX_PLAIN_VALUES;

    private YamlDocument() {
    }

    /**
     * @param file the file
     * @return a reader on its top-level mapping; check its problems when done
     * @throws io.robomw.config.description.DescriptionException if the file cannot be read or is not YAML within the limits
     */
    public static MappingReader read(Path file) {
        Problems problems = new Problems(file.toString());
        byte[] bytes = null;
        if (Files.isDirectory(file)) {
            problems.add(null, "this is a directory, not a YAML file");
        } else if (Files.exists(file) && !Files.isRegularFile(file)) {
            problems.add(null, "this is not a regular file (a FIFO, a device or a socket): refused without reading it");
        } else {
            try (InputStream in = Files.newInputStream(file)) {
                bytes = in.readNBytes(MAX_FILE_BYTES + 1);
            } catch (NoSuchFileException e) {
                problems.add(null, "no such file");
            } catch (AccessDeniedException e) {
                problems.add(null, "this file may not be read (permission denied)");
            } catch (IOException e) {
                problems.add(null, "cannot read the file: " + (e.getMessage() == null ? "the system gave no reason" : e.getMessage()));
            }
        }
        if (bytes != null && bytes.length > MAX_FILE_BYTES) {
            problems.add(null, "the file is larger than 1 MiB (" + MAX_FILE_BYTES + " bytes), the limit for robot and world files;"
                    + " is it the right file?");
        }
        problems.throwIfAny();
        String text = utf8(bytes, problems);
        problems.throwIfAny();
        return parse(text, file.toString());
    }

    /**
     * Decodes strict UTF-8; the first byte that is not UTF-8 is reported where it is.
     *
     * @return the text, or {@code null} after recording the problem
     */
    private static String utf8(byte[] bytes, Problems problems) {
        CharsetDecoder decoder = StandardCharsets.UTF_8.newDecoder()
                .onMalformedInput(CodingErrorAction.REPORT).onUnmappableCharacter(CodingErrorAction.REPORT);
        ByteBuffer in = ByteBuffer.wrap(bytes);
        CharBuffer out = CharBuffer.allocate(bytes.length);
        CoderResult result = decoder.decode(in, out, true);
        if (!result.isError()) {
            result = decoder.flush(out);
        }
        if (result.isError()) {
            out.flip();
            int line = 0;
            int column = 0;
            for (int i = 0; i < out.limit(); i++) {
                if (out.get(i) == '\n') {
                    line++;
                    column = 0;
                } else {
                    column++;
                }
            }
            problems.add(new Mark("", 0, line, column, new int[0], 0), String.format(
                    "the file is not UTF-8 text: byte 0x%02X here cannot be part of a UTF-8 character; save the file as UTF-8",
                    bytes[in.position()] & 0xFF));
            return null;
        }
        out.flip();
        return out.toString();
    }

    /**
     * @param text   YAML text
     * @param source its name in messages
     * @return a reader on its top-level mapping
     * @throws io.robomw.config.description.DescriptionException if it is not YAML within the limits, or not a mapping
     */
    public static MappingReader parse(String text, String source) {
        Problems problems = new Problems(source);
        if (text.length() > MAX_FILE_BYTES) {
            problems.add(null, "the text is longer than " + MAX_FILE_BYTES + " characters, the limit for robot and world files");
            problems.throwIfAny();
        }
        LoaderOptions options = new LoaderOptions();
        options.setCodePointLimit(MAX_FILE_BYTES);
        options.setMaxAliasesForCollections(MAX_COLLECTION_ALIASES);
        options.setNestingDepthLimit(MAX_DEPTH + 10);
        options.setAllowRecursiveKeys(false);
        options.setAllowDuplicateKeys(false);
        Node root;
        try {
            checkEvents(new Yaml(options).parse(new StringReader(text)), problems);
            problems.throwIfAny();
            root = new Yaml(options).compose(new StringReader(text));
        } catch (MarkedYAMLException e) {
            problems.add(e.getProblemMark(), "not valid YAML: " + e.getProblem());
            problems.throwIfAny();
            throw new AssertionError(e);
        } catch (YAMLException e) {
            problems.add(null, "not valid YAML: " + e.getMessage());
            problems.throwIfAny();
            throw new AssertionError(e);
        }
        if (root == null) {
            problems.add(null, "the file is empty; expected a mapping of keys to values");
            problems.throwIfAny();
        }
        if (!(root instanceof MappingNode mapping)) {
            problems.add(root.getStartMark(), "expected a mapping of keys to values at the top of the file");
            problems.throwIfAny();
            throw new AssertionError();
        }
        checkKeys(mapping, problems);
        return new MappingReader(mapping, "", problems);
    }

    /** An open list or mapping while the events are checked: its anchor, and how many values it expands to so far. */
    private static final class Open {
        final String anchor;
        long values = 1;

        Open(String anchor) {
            this.anchor = anchor;
        }
    }

    /**
     * Checks the nesting depth and the aliases from the parser's events, before anything is built:
     * a self-referencing alias, too many aliases and an alias bomb are refused at the alias, with
     * its line and column. Stops at the first such problem.
     */
    private static void checkEvents(Iterable<Event> events, Problems problems) {
        Deque<Open> open = new ArrayDeque<>();
        Set<String> openAnchors = new HashSet<>();
        Map<String, Long> sizes = new HashMap<>();
        long total = 0;
        int collectionAliases = 0;
        for (Event e : events) {
            long added;
            if (e instanceof CollectionStartEvent start) {
                if (open.size() >= MAX_DEPTH) {
                    problems.add(e.getStartMark(), "lists and mappings are nested more than " + MAX_DEPTH + " levels deep here; "
                            + "robot and world files need a few");
                    return;
                }
                open.push(new Open(start.getAnchor()));
                if (start.getAnchor() != null) {
                    openAnchors.add(start.getAnchor());
                }
                added = 1;
            } else if (e instanceof CollectionEndEvent) {
                Open done = open.pop();
                if (done.anchor != null) {
                    openAnchors.remove(done.anchor);
                    sizes.put(done.anchor, done.values);
                }
                if (!open.isEmpty()) {
                    open.peek().values += done.values;
                }
                continue;
            } else if (e instanceof ScalarEvent scalar) {
                if (scalar.getAnchor() != null) {
                    sizes.put(scalar.getAnchor(), 1L);
                }
                added = 1;
            } else if (e instanceof AliasEvent alias) {
                String name = alias.getAnchor();
                if (openAnchors.contains(name)) {
                    problems.add(e.getStartMark(), "the alias *" + name + " is inside the value anchored &" + name
                            + " it refers to, so that value would contain itself without end; write the inner value out instead");
                    return;
                }
                Long size = sizes.get(name);
                if (size == null) {
                    problems.add(e.getStartMark(), "the alias *" + name + " refers to no anchor: write &" + name
                            + " on a value before it, or write the value out");
                    return;
                }
                if (size > 1 && ++collectionAliases > MAX_COLLECTION_ALIASES) {
                    problems.add(e.getStartMark(), "more than " + MAX_COLLECTION_ALIASES
                            + " aliases to lists or mappings (an alias bomb?); write the values out instead");
                    return;
                }
                added = size;
            } else {
                continue;
            }
            total += added;
            if (!open.isEmpty() && !(e instanceof CollectionStartEvent)) {
                open.peek().values += added;
            }
            if (total > MAX_VALUES) {
                problems.add(e.getStartMark(), "through its aliases the file expands to more than " + MAX_VALUES
                        + " values here (an alias bomb?); write the values out instead of repeating them with aliases");
                return;
            }
        }
    }

    /**
     * Checks every mapping of the file once (also those only reached through aliases, and those whose
     * keys belong to a platform): keys are plain names, none twice.
     */
    private static void checkKeys(MappingNode root, Problems problems) {
        Deque<Node> todo = new ArrayDeque<>();
        Map<Node, String> paths = new IdentityHashMap<>();
        todo.push(root);
        paths.put(root, "");
        while (!todo.isEmpty()) {
            Node n = todo.pop();
            String path = paths.get(n);
            if (n instanceof MappingNode m) {
                Set<String> seen = new HashSet<>();
                for (NodeTuple t : m.getValue()) {
                    if (!(t.getKeyNode() instanceof ScalarNode key)) {
                        problems.add(t.getKeyNode().getStartMark(), "keys must be plain names" + (path.isEmpty() ? "" : " in '" + path + "'"));
                        continue;
                    }
                    String where = path.isEmpty() ? key.getValue() : path + "." + key.getValue();
                    if (!seen.add(key.getValue())) {
                        problems.add(key.getStartMark(), "key '" + Problems.quote(where) + "' appears twice; keep one");
                    }
                    visit(t.getValueNode(), where, todo, paths);
                }
            } else if (n instanceof SequenceNode s) {
                for (int i = 0; i < s.getValue().size(); i++) {
                    visit(s.getValue().get(i), path + "[" + i + "]", todo, paths);
                }
            }
        }
    }

    private static void visit(Node n, String path, Deque<Node> todo, Map<Node, String> paths) {
        if (!(n instanceof ScalarNode) && paths.putIfAbsent(n, path) == null) {
            todo.push(n);
        }
    }
}
