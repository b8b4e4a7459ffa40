package io.robomw.it.net;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.AgentRef;
import io.robomw.api.Itinerary;

import java.io.BufferedReader;
import java.io.InputStreamReader;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Arrays;
import java.util.List;
import java.util.stream.Collectors;

/**
 * An agents' home in a namespace of a {@link NetLab}: an agent host bound to the namespace's
 * address that sends {@link HopAgent}s and prints what comes back, one line each:
 * {@code REPORT ID VALUE}, {@code RESULT ID KEY,KEY,...}, {@code FAILED ID WHY},
 * {@code HISTORY ID OUTCOME@HOST;...}. Arguments: {@code NAME IP KEY-FILE}. Commands on stdin:
 * <ul>
 *   <li>{@code trip WORK-MS RETRIES BACKOFF-MS HOST,HOST,...}: one agent over those stops, retrying an
 *       unreachable one RETRIES times BACKOFF-MS apart, then skipping it; prints {@code SENT ID};</li>
 *   <li>{@code clones WORK-MS RETRIES BACKOFF-MS TOUR-HOST,... FIRST-HOST,...}: a clone to each first
 *       host, each going on over the tour; prints {@code SENT ID} per clone;</li>
 *   <li>{@code exit}.</li>
 * </ul>
 */
public final class TripHome {

    private TripHome() {
    }

    /**
     * @param args name, bind address, key file
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        try (AgentHost home = AgentHost.builder(args[0]).bind(args[1]).port(1099).clusterKey(ClusterKey.read(Path.of(args[2]))).noMessaging()
                .callTimeout(Duration.ofSeconds(5)).start()) {
            out.println("READY " + home.address());
            BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
            for (String line; (line = in.readLine()) != null && !line.equals("exit"); ) {
                String[] c = line.split(" ");
                try {
                    switch (c[0]) {
                        case "trip" -> {
                            HopAgent agent = new HopAgent(Integer.parseInt(c[1]), List.of());
                            patience(agent.itinerary(), c);
                            Arrays.stream(c[4].split(",")).forEach(agent.itinerary()::addStop);
                            follow(out, home.agency().startTrip(agent));
                        }
                        case "clones" -> {
                            HopAgent agent = new HopAgent(Integer.parseInt(c[1]), List.of(c[4].split(",")));
                            patience(agent.itinerary(), c);
                            for (AgentRef ref : home.agency().dispatchClones(agent, c[5].split(","))) {
                                follow(out, ref);
                            }
                        }
                        default -> out.println("ERR unknown command " + c[0]);
                    }
                } catch (RuntimeException e) {
                    out.println("ERR " + String.valueOf(e.getMessage()).replace('\n', ' '));
                }
            }
        }
        out.println("BYE");
    }

    private static void patience(Itinerary it, String[] c) {
        it.onUnreachable(Itinerary.UnreachablePolicy.RETRY).retry(Integer.parseInt(c[2]), Duration.ofMillis(Long.parseLong(c[3])));
    }

    private static void follow(PrintStream out, AgentRef ref) {
        ref.addReportListener(r -> out.println("REPORT " + ref.id() + " " + r));
        ref.result().whenComplete((v, e) -> {
            out.println("HISTORY " + ref.id() + " " + ref.history().stream()
                    .map(visit -> visit.outcome() + "@" + visit.host() + (visit.detail() == null || visit.detail().isEmpty() ? "" : "(" + visit.detail().replace('\n', ' ') + ")"))
                    .collect(Collectors.joining(";")));
            out.println(e == null ? "RESULT " + ref.id() + " " + (v instanceof List<?> l ? l.stream().map(String::valueOf).collect(Collectors.joining(",")) : v)
                    : "FAILED " + ref.id() + " " + String.valueOf(e.getMessage()).replace('\n', ' '));
        });
        out.println("SENT " + ref.id());
    }
}
