package io.robomw.cli;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * A copy of a robot file whose {@code connection:} points somewhere else (an emulator's
 * pseudo-terminal or TCP port), written as text so that the user's comments and layout stay: the
 * connection's {@code port} and {@code host} lines are replaced, every other line is kept.
 */
final class ReadyRobotFile {

    private static final Pattern BLOCK_START = Pattern.compile("^connection:\\s*(#.*)?$");
    private static final Pattern FLOW = Pattern.compile("^connection:\\s*\\{(.*)}\\s*(#.*)?$");
    private static final Pattern KEY = Pattern.compile("^(\\s+)([A-Za-z_]+)\\s*:.*$");

    private ReadyRobotFile() {
    }

    /**
     * @param source     the robot file
     * @param target     where the copy goes (replaced if it exists)
     * @param connection the connection values to set ({@code port}, and {@code host} for TCP); other keys are kept
     * @param madeBy     the command that wrote it, for its first comment
     * @throws IOException if the source cannot be read or the target written
     */
    static void write(Path source, Path target, Map<String, String> connection, String madeBy) throws IOException {
        List<String> lines = Files.readAllLines(source, StandardCharsets.UTF_8);
        List<String> out = new ArrayList<>();
        out.add("# Written by " + madeBy + " from " + source + ": its connection is the emulator's; the rest is the robot file's.");
        boolean done = false;
        for (int i = 0; i < lines.size(); i++) {
            String line = lines.get(i);
            Matcher flow = FLOW.matcher(line);
            if (!done && flow.matches()) {
                Map<String, String> kept = new LinkedHashMap<>();
                for (String entry : flow.group(1).split(",")) {
                    int colon = entry.indexOf(':');
                    if (colon > 0) {
                        kept.put(entry.substring(0, colon).strip(), entry.substring(colon + 1).strip());
                    }
                }
                kept.keySet().removeAll(List.of("port", "host"));
                out.add("connection:");
                connection.forEach((k, v) -> out.add("  " + k + ": " + v));
                kept.forEach((k, v) -> out.add("  " + k + ": " + v));
                done = true;
            } else if (!done && BLOCK_START.matcher(line).matches()) {
                out.add("connection:");
                String indent = "  ";
                List<String> rest = new ArrayList<>();
                int j = i + 1;
                for (; j < lines.size(); j++) {
                    String l = lines.get(j);
                    if (!l.isBlank() && !Character.isWhitespace(l.charAt(0)) && !l.startsWith("#")) {
                        break;
                    }
                    Matcher key = KEY.matcher(l);
                    if (key.matches()) {
                        indent = key.group(1);
                        if (connection.containsKey(key.group(2)) || key.group(2).equals("host") || key.group(2).equals("port")) {
                            continue;
                        }
                    }
                    rest.add(l);
                }
                String in = indent;
                connection.forEach((k, v) -> out.add(in + k + ": " + v));
                out.addAll(rest);
                i = j - 1;
                done = true;
            } else {
                out.add(line);
                if (!done && line.startsWith("platform:")) {
                    // A file without a connection gets one after its platform, unless one comes later.
                    if (lines.stream().noneMatch(l -> BLOCK_START.matcher(l).matches() || FLOW.matcher(l).matches())) {
                        out.add("connection:");
                        connection.forEach((k, v) -> out.add("  " + k + ": " + v));
                        done = true;
                    }
                }
            }
        }
        Path parent = target.toAbsolutePath().getParent();
        if (parent != null) {
            Files.createDirectories(parent);
        }
        // Whole or not at all: a command waiting for the file (AwaitedFile) never reads half of it.
        Path partial = Files.createTempFile(parent != null ? parent : Path.of("."), "." + target.getFileName(), ".part");
        try {
            Files.write(partial, out, StandardCharsets.UTF_8);
            Files.move(partial, target, java.nio.file.StandardCopyOption.REPLACE_EXISTING, java.nio.file.StandardCopyOption.ATOMIC_MOVE);
        } finally {
            Files.deleteIfExists(partial);
        }
    }
}
