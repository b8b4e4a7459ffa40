package io.robomw.config.description;

import io.robomw.api.RobotException;

import java.util.List;
import java.util.stream.Collectors;

/**
 * A robot or world description is invalid. The message lists every problem found, each with
 * file, line and column.
 */
public class DescriptionException extends RobotException {

    private static final long serialVersionUID = 1L;

    private final transient List<Problem> problems;

    /**
     * @param problems what is wrong, at least one
     */
    public DescriptionException(List<Problem> problems) {
        super(problems.size() == 1 ? problems.get(0).toString()
                : problems.size() + " problems:\n" + problems.stream().map(p -> "  " + p).collect(Collectors.joining("\n")));
        this.problems = List.copyOf(problems);
    }

    /** @return every problem, in file order */
    public List<Problem> problems() {
        return problems;
    }

    /**
     * One problem at one place of a file.
     *
     * @param file    the file
     * @param line    1-based line
     * @param column  1-based column
     * @param message what is wrong and what is expected
     */
    public record Problem(String file, int line, int column, String message) {
        @Override
        public String toString() {
            return file + ":" + line + ":" + column + ": " + message;
        }
    }
}
