/**
 * The home side: the agents sent from a host, their handles and requests (messages, retract,
 * dispose), and the reports and results owed to homes and delivered to them. Internal to the agent
 * host.
 */
package io.robomw.agents.host.home;
