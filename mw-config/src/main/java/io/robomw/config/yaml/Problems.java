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
        found.add(new Problem(file, mark == null ? 1 : mark.getLine() + 1, mark == null ? 1 : mark.getColumn() + 1, message));
    }

    /**
     * Spends one plain value of the file's budget.
     *
     * @return false once the budget is spent
     */
    boolean spendValue() {
        return --valueBudget >= 0;
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
            throw new DescriptionException(sorted);
        }
    }
}
