package io.robomw.cli;

import java.lang.reflect.RecordComponent;
import java.util.Collection;
import java.util.Map;

/** Writes agents' results for people: a record as one "name: value" line per component, anything else by its toString. */
final class ResultText {

    private ResultText() {
    }

    static String format(Object value, String indent) {
        if (value == null) {
            return indent + "(no result)";
        }
        if (value.getClass().isRecord()) {
            StringBuilder b = new StringBuilder();
            for (RecordComponent c : value.getClass().getRecordComponents()) {
                Object v;
                try {
                    c.getAccessor().setAccessible(true);
                    v = c.getAccessor().invoke(value);
                } catch (ReflectiveOperationException | RuntimeException e) {
                    v = "?";
                }
                if (b.length() > 0) {
                    b.append('\n');
                }
                b.append(indent).append(c.getName()).append(": ").append(brief(v));
            }
            return b.toString();
        }
        return indent + brief(value);
    }

    private static String brief(Object v) {
        if (v instanceof Collection<?> c && c.size() > 12) {
            return c.stream().limit(12).map(String::valueOf).toList() + " ... (" + c.size() + " in all)";
        }
        if (v instanceof Map<?, ?> m && m.size() > 12) {
            return m.size() + " entries";
        }
        if (v instanceof Double d) {
            return String.format("%.4f", d);
        }
        return String.valueOf(v);
    }
}
