/**
 * The agent host protocol's layouts and codes: operations ({@link io.robomw.agents.host.protocol.Op}),
 * replies, call bodies ({@link io.robomw.agents.host.protocol.Bodies}), agent images and events, and
 * the frames that carry them. Internal to the agent host: no other module uses it.
 */
package io.robomw.agents.host.protocol;
