package io.robomw.console.foxglove;

import java.util.Arrays;
import java.util.HashSet;
import java.util.List;
import java.util.Optional;
import java.util.Set;

/**
 * The WebSocket subprotocols RoboMW's Foxglove server speaks, named in the handshake's
 * {@code Sec-WebSocket-Protocol} header. Both are the same protocol under two names: Foxglove
 * renamed {@code foxglove.websocket.v1} (the legacy specification, foxglove/ws-protocol) to
 * {@code foxglove.sdk.v1} (the Foxglove SDK, and foxglove_bridge from 3.2, which refuse the old
 * name). RoboMW accepts both, so older clients (Lichtblick before it learnt the new name,
 * {@code @foxglove/ws-protocol}'s {@code FoxgloveClient}) connect as well as new ones; a handshake
 * offering neither gets HTTP 400, as the SDK answers.
 */
public enum Subprotocol {

    /** The Foxglove SDK's name, preferred when a client offers both. */
    SDK_V1("foxglove.sdk.v1"),
    /** The legacy specification's name. */
    WEBSOCKET_V1("foxglove.websocket.v1");

    private final String wire;

    Subprotocol(String wire) {
        this.wire = wire;
    }

    /** @return its name in the handshake */
    public String wire() {
        return wire;
    }

    /**
     * Chooses the subprotocol to answer a handshake with.
     *
     * @param offered what the client's {@code Sec-WebSocket-Protocol} headers list (each entry may
     *                itself be a comma-separated list, as a header value is)
     * @return {@link #SDK_V1} if offered, else {@link #WEBSOCKET_V1} if offered, else empty
     */
    public static Optional<Subprotocol> choose(List<String> offered) {
        Set<String> names = new HashSet<>();
        for (String header : offered) {
            for (String name : header.split(",")) {
                names.add(name.trim());
            }
        }
        return Arrays.stream(values()).filter(p -> names.contains(p.wire)).findFirst(); // values() in order of preference
    }
}
