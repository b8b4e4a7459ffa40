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

    /**
     * @param agent  an agent that came home (retracted)
     * @param indent the indent of each line
     * @return its class and one "name: value" line per field it carries (not static, not transient)
     */
    static String state(io.robomw.api.Agent agent, String indent) {
        StringBuilder b = new StringBuilder(indent).append(agent.getClass().getName());
        for (Class<?> c = agent.getClass(); c != null && c != io.robomw.api.Agent.class; c = c.getSuperclass()) {
            for (java.lang.reflect.Field f : c.getDeclaredFields()) {
                int m = f.getModifiers();
                if (java.lang.reflect.Modifier.isStatic(m) || java.lang.reflect.Modifier.isTransient(m)) {
                    continue;
                }
                Object v;
                try {
                    f.setAccessible(true);
                    v = f.get(agent);
                } catch (ReflectiveOperationException | RuntimeException e) {
                    v = "?";
                }
                b.append('\n').append(indent).append("  ").append(f.getName()).append(": ").append(brief(v));
            }
        }
        return b.toString();
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
