package io.robomw.console.rosbridge.protocol;

import java.util.Locale;

/**
 * How a subscription wants its messages: a {@code subscribe}'s {@code compression}.
 *
 * <table>
 *   <caption>values</caption>
 *   <tr><th>wire</th><th>here</th></tr>
 *   <tr><td>{@code none} (or absent)</td><td>JSON text frames</td></tr>
 *   <tr><td>{@code cbor}</td><td>binary frames, one CBOR map each ({@link io.robomw.console.rosbridge.msg.Wire})</td></tr>
 *   <tr><td>{@code png}</td><td>not offered: JSON text frames instead, with a warning (every rosbridge client
 *   that asks for png also reads plain {@code publish} frames)</td></tr>
 *   <tr><td>{@code cbor-raw}</td><td>refused: it carries messages in ROS 2's own serialisation (CDR), which this bridge does not write</td></tr>
 * </table>
 */
public enum Compression {
    /** JSON text. */
    NONE("none"),
    /** One CBOR map per message, in a binary frame. */
    CBOR("cbor");

    private final String wire;

    Compression(String wire) {
        this.wire = wire;
    }

    /** @return its name on the wire */
    public String wire() {
        return wire;
    }

    /**
     * @param wire the value a client sent, or {@code null}
     * @return the compression to use; {@code png} gives {@link #NONE} (the caller warns)
     * @throws IllegalArgumentException for {@code cbor-raw} and unknown values
     */
    public static Compression of(String wire) {
        if (wire == null) {
            return NONE;
        }
        return switch (wire.toLowerCase(Locale.ROOT)) {
            case "none", "", "png" -> NONE;
            case "cbor" -> CBOR;
            case "cbor-raw" -> throw new IllegalArgumentException("compression cbor-raw carries ROS 2's own serialisation (CDR), which this bridge "
                    + "does not write; use cbor or none");
            default -> throw new IllegalArgumentException("unknown compression '" + wire + "': use none or cbor");
        };
    }
}
