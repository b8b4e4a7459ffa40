package io.robomw.it.net;

import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.function.BooleanSupplier;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * What a {@link TripHome} printed, agent by agent, and the checks every scenario makes: every
 * agent sent came home with a result, every stop of its result reported exactly once, no stop
 * run twice (one key, two nonces), no report delivered twice.
 */
final class TripLog {

    private final LabProcess home;
    private final List<String> sent = new ArrayList<>();
    /** Agent id to the reports delivered, in order (duplicates kept). */
    private final Map<String, List<String>> reports = new LinkedHashMap<>();
    private final Map<String, List<String>> results = new LinkedHashMap<>();
    private final Map<String, String> histories = new LinkedHashMap<>();
    private final Map<String, String> failures = new LinkedHashMap<>();

    TripLog(LabProcess home) {
        this.home = home;
    }

    /** Sends a command to the home and reads the {@code SENT} lines it answers with (one per agent). */
    List<String> send(String command, int agents, Duration within) {
        home.send(command);
        List<String> ids = new ArrayList<>();
        await("the home sends " + agents + " agent(s) (" + command + ")", within, () -> {
            ids.clear();
            ids.addAll(sent);
            return sent.size() >= agents;
        });
        return List.copyOf(ids);
    }

    /** Reads the home's lines until the condition holds, failing after the deadline. */
    void await(String what, Duration within, BooleanSupplier condition) {
        long deadline = System.nanoTime() + within.toNanos();
        while (!condition.getAsBoolean()) {
            long left = deadline - System.nanoTime();
            if (left <= 0) {
                fail("not within " + within + ": " + what + "; the home printed:\n" + home.output());
            }
            String line = home.next(Duration.ofNanos(Math.min(left, Duration.ofSeconds(1).toNanos())));
            if (line != null) {
                take(line);
            } else if (!home.alive()) {
                fail("the home ended while waiting: " + what + "; it printed:\n" + home.output());
            }
        }
    }

    /** Reads whatever the home prints until it says BYE (after {@code exit}): late duplicates are counted too. */
    void drain(Duration within) {
        home.send("exit");
        long deadline = System.nanoTime() + within.toNanos();
        for (String line; (line = home.next(Duration.ofNanos(Math.max(1, deadline - System.nanoTime())))) != null; ) {
            if (line.equals("BYE")) {
                return;
            }
            take(line);
        }
    }

    private void take(String line) {
        String[] p = line.split(" ", 3);
        switch (p[0]) {
            case "SENT" -> sent.add(p[1]);
            case "REPORT" -> reports.computeIfAbsent(p[1], k -> new ArrayList<>()).add(p[2]);
            case "RESULT" -> results.put(p[1], p.length < 3 || p[2].isEmpty() ? List.of() : List.of(p[2].split(",")));
            case "HISTORY" -> histories.put(p[1], p.length < 3 ? "" : p[2]);
            case "FAILED" -> failures.put(p[1], p.length < 3 ? "" : p[2]);
            case "ERR" -> fail("the home refused a command: " + line);
            default -> {
            }
        }
    }

    /** @return whether every agent sent has its result (or failure) home */
    boolean allHome() {
        return !sent.isEmpty() && sent.stream().allMatch(id -> results.containsKey(id) || failures.containsKey(id));
    }

    /** @return whether every stop in every result has been reported */
    boolean allReported() {
        return results.entrySet().stream().allMatch(e -> {
            Set<String> keys = new LinkedHashSet<>();
            reports.getOrDefault(e.getKey(), List.of()).forEach(r -> keys.add(r.substring(0, r.indexOf('/'))));
            return keys.containsAll(e.getValue());
        });
    }

    /** @param id an agent @return its history line: {@code OUTCOME@HOST(detail);...} */
    String history(String id) {
        return histories.getOrDefault(id, "");
    }

    /** @param id an agent @return the keys of its stops, from its result */
    List<String> result(String id) {
        return results.getOrDefault(id, List.of());
    }

    /** @return how many reports were delivered in all */
    int reportsDelivered() {
        return reports.values().stream().mapToInt(List::size).sum();
    }

    /** The checks of every scenario: nothing lost, nothing duplicated, no stop run twice. */
    void assertNothingLostOrDuplicated() {
        assertTrue(failures.isEmpty(), "agents whose result failed: " + failures);
        for (String id : sent) {
            assertTrue(results.containsKey(id), "agent " + id + " came home; the home printed:\n" + home.output());
            List<String> keys = results.get(id);
            assertEquals(keys.size(), new LinkedHashSet<>(keys).size(), "agent " + id + " ran no stop twice: " + keys);
            List<String> delivered = reports.getOrDefault(id, List.of());
            assertEquals(delivered.size(), new LinkedHashSet<>(delivered).size(), "no report of agent " + id + " was delivered twice: " + delivered);
            List<String> reportedKeys = delivered.stream().map(r -> r.substring(0, r.indexOf('/'))).toList();
            assertEquals(reportedKeys.size(), new LinkedHashSet<>(reportedKeys).size(), "no stop of agent " + id + " ran twice: " + delivered);
            assertEquals(new LinkedHashSet<>(keys), new LinkedHashSet<>(reportedKeys), "agent " + id + ": every stop of its result reported once, no other");
        }
    }
}
