package io.robomw.cli;

import java.util.ArrayList;
import java.util.List;

/**
 * Splits a command line into words as a shell does for plain words and quotes ('...' and "...");
 * no variables, no escapes. For {@code mw up}'s command lines and the tests that run the commands
 * the docs show.
 */
public final class ShellWords {

    private ShellWords() {
    }

    /**
     * @param line a command line
     * @return its words, quotes removed
     * @throws IllegalArgumentException if a quote is not closed
     */
    public static List<String> split(String line) {
        List<String> words = new ArrayList<>();
        StringBuilder w = new StringBuilder();
        char quote = 0;
        boolean any = false;
        for (char c : line.toCharArray()) {
            if (quote != 0) {
                if (c == quote) {
                    quote = 0;
                } else {
                    w.append(c);
                }
            } else if (c == '\'' || c == '"') {
                quote = c;
                any = true;
            } else if (Character.isWhitespace(c)) {
                if (w.length() > 0 || any) {
                    words.add(w.toString());
                    w.setLength(0);
                    any = false;
                }
            } else {
                w.append(c);
            }
        }
        if (quote != 0) {
            throw new IllegalArgumentException("unclosed " + quote + " in: " + line);
        }
        if (w.length() > 0 || any) {
            words.add(w.toString());
        }
        return words;
    }
}
