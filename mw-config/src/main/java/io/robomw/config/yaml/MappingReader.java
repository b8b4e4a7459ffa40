package io.robomw.config.yaml;

import org.yaml.snakeyaml.error.Mark;
import org.yaml.snakeyaml.nodes.MappingNode;
import org.yaml.snakeyaml.nodes.Node;
import org.yaml.snakeyaml.nodes.NodeTuple;
import org.yaml.snakeyaml.nodes.ScalarNode;
import org.yaml.snakeyaml.nodes.SequenceNode;
import org.yaml.snakeyaml.nodes.Tag;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Optional;
import java.util.OptionalDouble;
import java.util.Set;
import java.util.TreeSet;
import java.util.function.DoublePredicate;

/**
 * Reads one YAML mapping key by key, checking types as it goes. Every problem is recorded with
 * its line and column in the shared {@link Problems}, and the reader returns a fallback so the
 * rest of the file is still checked; {@link #finish()} reports keys nobody asked for.
 *
 * <p>Not thread-safe; one reader per load.
 */
public final class MappingReader {

    private final MappingNode node;
    private final String path;
    private final Problems problems;
    private final Map<String, NodeTuple> entries = new LinkedHashMap<>();
    private final Set<String> asked = new HashSet<>();

    MappingReader(MappingNode node, String path, Problems problems) {
        this.node = node;
        this.path = path;
        this.problems = problems;
        // Keys that are not plain names, and keys given twice, are reported once for the whole file by YamlDocument.
        for (NodeTuple tuple : node.getValue()) {
            if (tuple.getKeyNode() instanceof ScalarNode key) {
                entries.putIfAbsent(key.getValue(), tuple);
            }
        }
    }

    /** @return the problems of this file */
    public Problems problems() {
        return problems;
    }

    /** @return the dotted path of this mapping in the file, empty for the top */
    public String path() {
        return path;
    }

    /** @return where this mapping starts */
    public Mark mark() {
        return node.getStartMark();
    }

    /**
     * @param key a key
     * @return where its value is, or where this mapping starts when the key is absent
     */
    public Mark mark(String key) {
        NodeTuple t = entries.get(key);
        return t == null ? node.getStartMark() : t.getValueNode().getStartMark();
    }

    /**
     * @param key a key
     * @return whether it is present
     */
    public boolean has(String key) {
        asked.add(key);
        return entries.containsKey(key);
    }

    /**
     * Records a problem at a key's value.
     *
     * @param key     the key
     * @param message what is wrong
     */
    public void problem(String key, String message) {
        problems.add(mark(key), "'" + where(key) + "': " + message);
    }

    /**
     * @param key a required key
     * @return its text, or "" after recording that it is missing
     */
    public String requireText(String key) {
        Optional<String> text = text(key, true);
        if (text.isPresent() && text.get().isBlank()) {
            problem(key, "must not be empty");
            return "";
        }
        return text.orElseGet(() -> {
            if (!entries.containsKey(key)) {
                missing(key, "a text value");
            }
            return "";
        });
    }

    /**
     * @param key a key
     * @return its scalar text, if present
     */
    public Optional<String> text(String key) {
        return text(key, false);
    }

    private Optional<String> text(String key, boolean required) {
        Node value = value(key, "a text value", required);
        if (value == null) {
            return Optional.empty();
        }
        if (value instanceof ScalarNode scalar && !scalar.getTag().equals(Tag.NULL)) {
            return Optional.of(scalar.getValue());
        }
        wrongType(key, value, "a text value");
        return Optional.empty();
    }

    /**
     * @param key      a key
     * @param fallback the value when absent or invalid
     * @param range    the values it may take, which also words the problem
     * @return its number
     */
    public double number(String key, double fallback, Range range) {
        return number(key, fallback, range.rule(), range);
    }

    /**
     * @param key   a required key
     * @param range the values it may take, which also words the problem
     * @return its number, or NaN after recording the problem
     */
    public double requireNumber(String key, Range range) {
        return requireNumber(key, range.rule(), range);
    }

    /**
     * @param key   a key
     * @param range the values it may take, which also words the problem
     * @return its number, if present and valid
     */
    public OptionalDouble optionalNumber(String key, Range range) {
        return optionalNumber(key, range.rule(), range);
    }

    /**
     * A number with a rule given twice, as words and as a check; prefer
     * {@link #number(String, double, Range)}, whose one {@link Range} makes both.
     *
     * @param key      a key
     * @param fallback the value when absent or invalid
     * @param rule     what a valid value is, in words, for example {@code "> 0"}
     * @param valid    the check
     * @return its number
     */
    public double number(String key, double fallback, String rule, DoublePredicate valid) {
        OptionalDouble v = optionalNumber(key, rule, valid);
        return v.isPresent() ? v.getAsDouble() : fallback;
    }

    /**
     * A required number with a rule given twice; prefer {@link #requireNumber(String, Range)}.
     *
     * @param key   a required key
     * @param rule  what a valid value is
     * @param valid the check
     * @return its number, or NaN after recording the problem
     */
    public double requireNumber(String key, String rule, DoublePredicate valid) {
        if (!entries.containsKey(key)) {
            missing(key, "a number " + rule);
            asked.add(key);
            return Double.NaN;
        }
        OptionalDouble v = number(key, rule, valid, true);
        return v.isPresent() ? v.getAsDouble() : Double.NaN;
    }

    /**
     * An optional number with a rule given twice; prefer {@link #optionalNumber(String, Range)}.
     *
     * @param key   a key
     * @param rule  what a valid value is
     * @param valid the check
     * @return its number, if present and valid
     */
    public OptionalDouble optionalNumber(String key, String rule, DoublePredicate valid) {
        return number(key, rule, valid, false);
    }

    private OptionalDouble number(String key, String rule, DoublePredicate valid, boolean required) {
        Node value = value(key, "a number " + rule, required);
        if (value == null) {
            return OptionalDouble.empty();
        }
        Double d = toNumber(value);
        if (d == null) {
            wrongType(key, value, "a number " + rule);
            return OptionalDouble.empty();
        }
        if (!Double.isFinite(d)) {
            problems.add(value.getStartMark(), "'" + where(key) + "' must be " + rule + ", got " + scalarText(value)
                    + ", a number too large to use");
            return OptionalDouble.empty();
        }
        if (!valid.test(d)) {
            problems.add(value.getStartMark(), "'" + where(key) + "' must be " + rule + ", got " + scalarText(value));
            return OptionalDouble.empty();
        }
        return OptionalDouble.of(d);
    }

    /**
     * @param key      a key
     * @param fallback the value when absent or invalid
     * @return its integer value
     */
    public int integer(String key, int fallback) {
        return integer(key, fallback, Integer.MIN_VALUE, Integer.MAX_VALUE);
    }

    /**
     * @param key      a key
     * @param fallback the value when absent or invalid
     * @param min      the smallest valid value
     * @param max      the largest valid value
     * @return its integer value, checked against the range
     */
    public int integer(String key, int fallback, int min, int max) {
        String expected = min == Integer.MIN_VALUE && max == Integer.MAX_VALUE ? "an integer" : "an integer from " + min + " to " + max;
        Node value = value(key, expected, false);
        if (value == null) {
            return fallback;
        }
        if (value instanceof ScalarNode s && s.getTag().equals(Tag.INT)) {
            try {
                int v = Integer.parseInt(s.getValue().replace("_", ""));
                if (v >= min && v <= max) {
                    return v;
                }
            } catch (NumberFormatException e) {
                // falls through to the type error
            }
        }
        wrongType(key, value, expected);
        return fallback;
    }

    /**
     * @param key      a key
     * @param fallback the value when absent
     * @return its boolean value
     */
    public boolean bool(String key, boolean fallback) {
        Node value = value(key, "true or false", false);
        if (value == null) {
            return fallback;
        }
        if (value instanceof ScalarNode s && s.getTag().equals(Tag.BOOL)) {
            return yamlTrue(s.getValue());
        }
        wrongType(key, value, "true or false");
        return fallback;
    }

    /**
     * Reads an enum constant, written in lower case with dashes or underscores ({@code front-left}).
     *
     * @param key      a key
     * @param type     the enum
     * @param fallback the value when absent or invalid; {@code null} makes the key required
     * @param <E>      the enum
     * @return the constant
     */
    public <E extends Enum<E>> E enumValue(String key, Class<E> type, E fallback) {
        Optional<String> text = text(key, fallback == null);
        if (text.isEmpty()) {
            if (fallback == null && !entries.containsKey(key)) {
                missing(key, "one of " + choices(type));
            }
            return fallback;
        }
        return parseEnum(type, text.get(), mark(key), where(key)).orElse(fallback);
    }

    /**
     * @param key  a key whose value is a list of enum names
     * @param type the enum
     * @param <E>  the enum
     * @return the constants, empty when absent
     */
    public <E extends Enum<E>> List<E> enumList(String key, Class<E> type) {
        List<E> out = new ArrayList<>();
        for (Node item : sequence(key)) {
            if (item instanceof ScalarNode s && !s.getTag().equals(Tag.NULL)) {
                parseEnum(type, s.getValue(), s.getStartMark(), where(key)).ifPresent(out::add);
            } else {
                problems.add(item.getStartMark(), "'" + where(key) + "' items must be one of " + choices(type));
            }
        }
        return out;
    }

    /**
     * @param key a key whose value is a mapping
     * @return a reader on it, if present
     */
    public Optional<MappingReader> mapping(String key) {
        return mapping(key, false);
    }

    private Optional<MappingReader> mapping(String key, boolean required) {
        Node value = value(key, "a mapping of keys to values", required);
        if (value == null) {
            return Optional.empty();
        }
        if (value instanceof MappingNode m) {
            return Optional.of(new MappingReader(m, where(key), problems));
        }
        wrongType(key, value, "a mapping of keys to values");
        return Optional.empty();
    }

    /**
     * @param key a required key whose value is a mapping
     * @return a reader on it, if present and a mapping
     */
    public Optional<MappingReader> requireMapping(String key) {
        if (!entries.containsKey(key)) {
            missing(key, "a mapping of keys to values");
            asked.add(key);
            return Optional.empty();
        }
        return mapping(key, true);
    }

    /**
     * @param key a key whose value is a list of mappings
     * @return a reader on each, empty when absent
     */
    public List<MappingReader> mappingList(String key) {
        List<MappingReader> out = new ArrayList<>();
        List<Node> items = sequence(key);
        for (int i = 0; i < items.size(); i++) {
            if (items.get(i) instanceof MappingNode m) {
                out.add(new MappingReader(m, where(key) + "[" + i + "]", problems));
            } else {
                problems.add(items.get(i).getStartMark(), "'" + where(key) + "[" + i + "]' must be a mapping of keys to values");
            }
        }
        return out;
    }

    /**
     * @param key a key whose value is a list of numbers
     * @return the numbers, empty when absent; items that are not numbers are reported
     */
    public List<Double> numberList(String key) {
        List<Double> out = new ArrayList<>();
        for (Node item : sequence(key)) {
            Double d = toNumber(item);
            if (d == null || !Double.isFinite(d)) {
                problems.add(item.getStartMark(), "'" + where(key) + "' items must be numbers" + (d == null ? "" : " of a usable size")
                        + ", got " + scalarText(item));
            } else {
                out.add(d);
            }
        }
        return out;
    }

    /**
     * @param key a key whose value is one text or a list of texts ({@code listen: tcp://...} or
     *            {@code listen: [tcp://..., udp://...]})
     * @return the texts, empty when absent; items that are not texts are reported
     */
    public List<String> textList(String key) {
        Node value = value(key, "a text value or a list of them", false);
        if (value instanceof ScalarNode scalar && !scalar.getTag().equals(Tag.NULL)) {
            if (scalar.getValue().isBlank()) {
                problem(key, "must not be empty");
                return List.of();
            }
            return List.of(scalar.getValue());
        }
        List<String> out = new ArrayList<>();
        for (Node item : sequence(key)) {
            if (item instanceof ScalarNode s && !s.getTag().equals(Tag.NULL) && !s.getValue().isBlank()) {
                out.add(s.getValue());
            } else {
                problems.add(item.getStartMark(), "'" + where(key) + "' items must be texts, got " + scalarText(item));
            }
        }
        return out;
    }

    /**
     * @param key a key whose value is a list of lists of numbers ({@code [[0, 1], [2, 3]]})
     * @return the rows with their marks
     */
    public List<NumberRow> numberRows(String key) {
        List<NumberRow> out = new ArrayList<>();
        for (Node item : sequence(key)) {
            if (!(item instanceof SequenceNode row)) {
                problems.add(item.getStartMark(), "'" + where(key) + "' items must be lists of numbers");
                continue;
            }
            double[] values = new double[row.getValue().size()];
            boolean ok = true;
            for (int i = 0; i < values.length; i++) {
                Double d = toNumber(row.getValue().get(i));
                if (d == null || !Double.isFinite(d)) {
                    problems.add(row.getValue().get(i).getStartMark(), "'" + where(key) + "' items must be numbers"
                            + (d == null ? "" : " of a usable size") + ", got " + scalarText(row.getValue().get(i)));
                    ok = false;
                } else {
                    values[i] = d;
                }
            }
            if (ok) {
                out.add(new NumberRow(values, row.getStartMark()));
            }
        }
        return out;
    }

    /**
     * A row of numbers and where it is.
     *
     * @param values the numbers
     * @param mark   where the row starts
     */
    public record NumberRow(double[] values, Mark mark) {
    }

    /**
     * Reads a mapping as plain data (strings, numbers, booleans, lists, maps) for blocks whose keys
     * belong to someone else (a platform's connection settings, sensor options).
     *
     * @param key a key
     * @return the plain map, empty when absent
     */
    public Map<String, Object> plainMap(String key) {
        Node value = value(key, "a mapping of keys to values", false);
        if (value == null) {
            return Map.of();
        }
        if (!(value instanceof MappingNode)) {
            wrongType(key, value, "a mapping of keys to values");
            return Map.of();
        }
        @SuppressWarnings("unchecked")
        Map<String, Object> map = (Map<String, Object>) plainChecked(value, where(key));
        return map;
    }

    /**
     * @return the keys of this mapping, in file order, each marked as asked for
     */
    public List<String> keys() {
        asked.addAll(entries.keySet());
        return List.copyOf(entries.keySet());
    }

    /**
     * Records every key of this mapping that no one asked for, with the keys that are known.
     */
    public void finish() {
        for (Map.Entry<String, NodeTuple> e : entries.entrySet()) {
            if (!asked.contains(e.getKey())) {
                problems.add(e.getValue().getKeyNode().getStartMark(), "unknown key '" + where(e.getKey()) + "'; known keys here: "
                        + String.join(", ", new TreeSet<>(asked)));
            }
        }
    }

    /**
     * @param key      a key
     * @param expected what its value should be, for the message when it has none
     * @param required whether the key must be given (then "leave it out" is no advice)
     * @return its value, or {@code null} when absent or empty (an empty value is reported: {@code port:} or
     *         {@code port: ~} is a mistake, never a way to ask for the default)
     */
    private Node value(String key, String expected, boolean required) {
        asked.add(key);
        NodeTuple t = entries.get(key);
        if (t == null) {
            return null;
        }
        Node v = t.getValueNode();
        if (v instanceof ScalarNode s && s.getTag().equals(Tag.NULL)) {
            problems.add(t.getKeyNode().getStartMark(), "'" + where(key) + "' has no value; write " + expected
                    + (required ? "" : ", or leave the key out"));
            return null;
        }
        return v;
    }

    private List<Node> sequence(String key) {
        Node value = value(key, "a list", false);
        if (value == null) {
            return List.of();
        }
        if (value instanceof SequenceNode s) {
            return s.getValue();
        }
        wrongType(key, value, "a list");
        return List.of();
    }

    private void missing(String key, String expected) {
        problems.add(node.getStartMark(), "missing key '" + where(key) + "': expected " + expected);
    }

    private void wrongType(String key, Node value, String expected) {
        problems.add(value.getStartMark(), "'" + where(key) + "' must be " + expected + ", got " + scalarText(value));
    }

    private String where(String key) {
        return Problems.quote(path.isEmpty() ? key : path + "." + key);
    }

    private static String scalarText(Node n) {
        if (n instanceof ScalarNode s) {
            return "'" + Problems.quote(s.getValue()) + "'";
        }
        return n instanceof SequenceNode ? "a list" : "a mapping";
    }

    private static Double toNumber(Node n) {
        if (n instanceof ScalarNode s && (s.getTag().equals(Tag.INT) || s.getTag().equals(Tag.FLOAT))) {
            try {
                return Double.valueOf(s.getValue().replace("_", ""));
            } catch (NumberFormatException e) {
                return null;
            }
        }
        return null;
    }

    private <E extends Enum<E>> Optional<E> parseEnum(Class<E> type, String text, Mark mark, String where) {
        String normalized = text.trim().toUpperCase(Locale.ROOT).replace('-', '_').replace(' ', '_');
        try {
            return Optional.of(Enum.valueOf(type, normalized));
        } catch (IllegalArgumentException e) {
            problems.add(mark, "'" + where + "' must be one of " + choices(type) + ", got '" + text + "'");
            return Optional.empty();
        }
    }

    private static <E extends Enum<E>> String choices(Class<E> type) {
        return String.join(", ", Arrays.stream(type.getEnumConstants()).map(c -> c.name().toLowerCase(Locale.ROOT).replace('_', '-')).toList());
    }

    /** YAML 1.1 booleans as SnakeYAML resolves them: true, yes, on (any case). */
    private static boolean yamlTrue(String text) {
        String t = text.toLowerCase(Locale.ROOT);
        return t.equals("true") || t.equals("yes") || t.equals("on");
    }

    private Object plainChecked(Node n, String where) {
        try {
            return plain(n, where);
        } catch (BudgetSpent e) {
            problems.add(n.getStartMark(), "'" + where + "' expands to more than " + Problems.MAX_PLAIN_VALUES
                    + " values (an alias bomb?); refused");
            return Map.of();
        }
    }

    /** Thrown when a block expands past the file's value budget. */
    private static final class BudgetSpent extends RuntimeException {
        private static final long serialVersionUID = 1L;

        BudgetSpent() {
            super(null, null, false, false);
        }
    }

    /** Plain data of a block; empty values and numbers too large to use are reported with their path. */
    private Object plain(Node n, String where) {
        if (!problems.spendValue()) {
            throw new BudgetSpent();
        }
        if (n instanceof MappingNode m) {
            Map<String, Object> map = new LinkedHashMap<>();
            for (NodeTuple t : m.getValue()) {
                if (t.getKeyNode() instanceof ScalarNode k) {
                    String inner = where + "." + Problems.quote(k.getValue());
                    Node valueNode = t.getValueNode();
                    if (valueNode instanceof ScalarNode s && s.getTag().equals(Tag.NULL)) {
                        problems.add(k.getStartMark(), "'" + inner + "' has no value; write one, or leave the key out");
                        continue;
                    }
                    Object v = plain(valueNode, inner);
                    if (v != null) {
                        map.putIfAbsent(k.getValue(), v);
                    }
                }
            }
            return Map.copyOf(map);
        }
        if (n instanceof SequenceNode s) {
            List<Object> items = new ArrayList<>();
            for (int i = 0; i < s.getValue().size(); i++) {
                Node item = s.getValue().get(i);
                if (item instanceof ScalarNode sc && sc.getTag().equals(Tag.NULL)) {
                    problems.add(item.getStartMark(), "'" + where + "[" + i + "]' has no value; write one, or leave the item out");
                    continue;
                }
                Object v = plain(item, where + "[" + i + "]");
                if (v != null) {
                    items.add(v);
                }
            }
            return List.copyOf(items);
        }
        ScalarNode s = (ScalarNode) n;
        Tag tag = s.getTag();
        if (tag.equals(Tag.NULL)) {
            return null;
        }
        if (tag.equals(Tag.INT) || tag.equals(Tag.FLOAT)) {
            if (tag.equals(Tag.INT)) {
                try {
                    return Long.valueOf(s.getValue().replace("_", ""));
                } catch (NumberFormatException e) {
                    // too large for a long, or not decimal: as a floating-point number below
                }
            }
            Double d = toNumber(s);
            if (d == null) {
                return s.getValue();
            }
            if (!Double.isFinite(d)) {
                problems.add(s.getStartMark(), "'" + where + "' is " + scalarText(s) + ", a number too large to use");
                return null;
            }
            return d;
        }
        if (tag.equals(Tag.BOOL)) {
            return yamlTrue(s.getValue());
        }
        return s.getValue();
    }
}
