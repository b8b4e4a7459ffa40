package io.robomw.it.console;

import io.robomw.api.Agent;

/**
 * Test agent: stays at its host, stop after stop (one host, many rounds), reporting each round. A
 * retract or dispose takes effect between two rounds, so it answers within a fraction of a
 * second. Its code lives in the test classes only: it travels to the hosts as an archive.
 */
public class LingeringAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private int rounds;

    @Override
    public void run() {
        rounds++;
        context().report("round " + rounds + " at " + context().hostName());
        long until = System.nanoTime() + 250_000_000L;
        while (System.nanoTime() < until) {
            try {
                Thread.sleep(50); // the agent's own work: lingering at its stop
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
        }
    }
}
