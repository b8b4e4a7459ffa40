/**
 * Asking and watching agent hosts from outside: {@link io.robomw.agents.host.ops.HostClient} for
 * {@code mw agents}, {@code mw retract} and {@code mw dispose}, {@link io.robomw.agents.host.ops.HostWatch}
 * for the console. Public API.
 */
package io.robomw.agents.host.ops;
