package io.robomw.config.yaml;

import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DescriptionException.Problem;
import org.yaml.snakeyaml.error.Mark;

import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;

/** Collects the problems of one file while it is read, so one load reports them all. */
public final class Problems {

    private final String file;
    private final List<Problem> found = new ArrayList<>();
    private int valueBudget = MAX_PLAIN_VALUES;

    /** Most plain values one file may expand to (aliases included), so an alias bomb is refused. */
    public static final int MAX_PLAIN_VALUES = 100_000;
    /** Most problems reported for one file; the rest are counted ("... and 250 more"). */
    public static final int MAX_REPORTED = 100;
    /** Longest piece of the file's own text (a value, a key) quoted in a message. */
    public static final int MAX_QUOTED = 60;

    private int unreported;

    /**
     * @param file the file being read, as it is named in messages
     */
    public Problems(String file) {
        this.file = file;
    }

    /** @return the file's name */
    public String file() {
        return file;
    }

    /**
     * Records a problem.
     *
     * @param mark    where it is (SnakeYAML marks are 0-based)
     * @param message what is wrong
     */
    public void add(Mark mark, String message) {
        if (found.size() >= MAX_REPORTED) {
            unreported++;
            return;
        }
        found.add(new Problem(file, mark == null ? 1 : mark.getLine() + 1, mark == null ? 1 : mark.getColumn() + 1, oneLine(message)));
    }

    /**
     * Makes text from the file fit in a one-line message: control characters (line breaks, tabs...)
     * are written as escapes, and text longer than {@value #MAX_QUOTED} characters is cut with "...".
     *
     * @param text a value or key as written in the file
     * @return the text to quote
     */
    public static String quote(String text) {
        String cut = text.length() > MAX_QUOTED ? text.substring(0, MAX_QUOTED) + "..." : text;
        return oneLine(cut);
    }

    private static String oneLine(String text) {
        StringBuilder b = null;
        for (int i = 0; i < text.length(); i++) {
            char c = text.charAt(i);
            if (Character.isISOControl(c) || c == '\u2028' || c == '\u2029') {
                if (b == null) {
                    b = new StringBuilder(text.length() + 8).append(text, 0, i);
                }
                b.append(switch (c) {
                    case '\n' -> "\\n";
                    case '\r' -> "\\r";
                    case '\t' -> "\\t";
                    default -> String.format("\\u%04x", (int) c);
                });
            } else if (b != null) {
                b.append(c);
            }
        }
        return b == null ? text : b.toString();
    }

    /**
     * Spends one plain value of the file's budget.
     *
     * @return false once the budget is spent
     */
    boolean spendValue() {
        return --valueBudget >= 0;
    }

    /** @return how many problems were found so far */
    public int count() {
        return found.size() + unreported;
    }

    /** @return whether nothing is wrong so far */
    public boolean isEmpty() {
        return found.isEmpty();
    }

    /**
     * @throws DescriptionException listing every problem in file order, if there is any
     */
    public void throwIfAny() {
        if (!found.isEmpty()) {
            List<Problem> sorted = new ArrayList<>(found);
            sorted.sort(Comparator.comparingInt(Problem::line).thenComparingInt(Problem::column));
            if (unreported > 0) {
                Problem last = sorted.get(sorted.size() - 1);
                sorted.add(new Problem(file, last.line(), last.column(), "... and " + unreported + " more problems not listed; fix these first"));
            }
            throw new DescriptionException(sorted);
        }
    }
}
