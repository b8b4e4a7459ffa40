/**
 * A host's messaging node as its agents and other hosts see it: the hosts it knows by name,
 * and deliveries through a broker. Internal to the agent host.
 */
package io.robomw.agents.host.messaging;
