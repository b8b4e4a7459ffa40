/**
 * The agent wire (protocol version 3): one framed, tagged connection per peer that carries hops
 * and calls, its server, readers and writers. Internal to the agent host.
 */
package io.robomw.agents.host.wire;
