package io.robomw.console.rosbridge.protocol;

import java.util.Locale;

/**
 * The levels of {@code status} messages, and of {@code set_level}.
 *
 * <p>rosbridge_suite's ROS 2 server sends no {@code status} message at all (its {@code log} only
 * writes to the server's log), and roslibpy raises on one ("No handler registered for operation
 * status"). So this bridge sends none to a client that never sent {@code set_level}: it logs
 * instead, as rosbridge_suite does. A client that sent {@code set_level} (the ROS 1 protocol's
 * way to ask for them, which roslibjs and rosbridge's own tests use) gets every status message at
 * its level or above; {@code none} turns them off again.
 *
 * <table>
 *   <caption>wire names</caption>
 *   <tr><th>level</th><th>wire</th><th>sent after set_level</th></tr>
 *   <tr><td>{@link #INFO}</td><td>{@code info}</td><td>info, warning, error</td></tr>
 *   <tr><td>{@link #WARNING}</td><td>{@code warning}</td><td>warning, error</td></tr>
 *   <tr><td>{@link #ERROR}</td><td>{@code error}</td><td>error (the protocol's default level)</td></tr>
 *   <tr><td>{@link #NONE}</td><td>{@code none}</td><td>nothing</td></tr>
 * </table>
 */
public enum StatusLevel {
    /** What the bridge did (subscribed, advertised). */
    INFO("info", 0),
    /** Something was not done as asked, but something was done (png sent as JSON). */
    WARNING("warning", 1),
    /** A request was refused. */
    ERROR("error", 2),
    /** No status messages. */
    NONE("none", 3);

    private final String wire;
    private final int severity;

    StatusLevel(String wire, int severity) {
        this.wire = wire;
        this.severity = severity;
    }

    /** @return its name on the wire */
    public String wire() {
        return wire;
    }

    /**
     * @param threshold the level a client set
     * @return whether a message of this level is sent at that setting
     */
    public boolean shownAt(StatusLevel threshold) {
        return this != NONE && threshold != NONE && severity >= threshold.severity;
    }

    /**
     * @param wire a {@code set_level}'s {@code level}
     * @return the level ({@code warn} and {@code err} are taken too, as rosbridge's log takes them)
     * @throws IllegalArgumentException for another value
     */
    public static StatusLevel of(String wire) {
        return switch (wire == null ? "" : wire.toLowerCase(Locale.ROOT)) {
            case "info" -> INFO;
            case "warning", "warn" -> WARNING;
            case "error", "err" -> ERROR;
            case "none" -> NONE;
            default -> throw new IllegalArgumentException("unknown status level '" + wire + "': use info, warning, error or none");
        };
    }
}
