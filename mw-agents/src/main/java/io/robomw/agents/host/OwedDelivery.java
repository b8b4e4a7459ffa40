package io.robomw.agents.host;

import java.time.Instant;
import java.util.UUID;

/**
 * Something a host owes an agent's home and has not delivered yet, as {@code mw agents} lists it.
 *
 * @param agent     the agent
 * @param seq       the event's number among the agent's reports and results
 * @param kind      what it is: REPORT, VISITS (the trip's visits, just before its end), RESULT, FAILED or DISPOSED
 * @param home      the home it is owed to
 * @param owedSince when the host began to owe it
 * @param attempts  how many tries have failed
 * @param lastError why the last try failed, or empty
 */
public record OwedDelivery(UUID agent, long seq, String kind, String home, Instant owedSince, int attempts, String lastError) {
}
