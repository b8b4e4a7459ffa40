/**
 * The agents visiting a host: taken in, run stop by stop with the robot lent to one at a time,
 * sent on (or home) along their itineraries, and resumed from the store after a restart. Internal to
 * the agent host.
 */
package io.robomw.agents.host.visit;
