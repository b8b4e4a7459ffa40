package io.robomw.it.agents;

import io.robomw.agents.host.AgentHost;
import io.robomw.api.AgentRef;

import java.io.BufferedReader;
import java.io.InputStreamReader;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;

/**
 * A dispatcher in its own JVM for {@link BrokerEventsIT}: an agent host (the agents' home) whose
 * messaging node is at a broker with a persistent session; sends a {@link ListenerAgent} to the
 * host given and prints what comes home ({@code REPORT ...}, {@code RESULT ...}). Arguments:
 * {@code BROKER-ADDRESS TARGET-HOST}; stdin {@code exit} ends it.
 */
public final class HomeProgram {

    private HomeProgram() {
    }

    /**
     * @param args the broker address (with its options) and the agent host to send the agent to
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        try (AgentHost home = AgentHost.builder("be-home").clusterKey(AgentTripIT.KEY).messaging(args[0]).start()) {
            out.println("READY " + home.address());
            AgentRef ref = home.agency().sendAgent(args[1], new ListenerAgent("poke", null));
            ref.addReportListener(r -> out.println("REPORT " + r));
            ref.result().whenComplete((v, e) -> out.println(e == null ? "RESULT " + v : "FAILED " + e));
            out.println("SENT " + ref.id());
            BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
            String line;
            while ((line = in.readLine()) != null && !line.equals("exit")) {
                // waits for the test to end it
            }
        }
        out.println("BYE");
    }
}
