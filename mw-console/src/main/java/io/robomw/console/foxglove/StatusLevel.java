package io.robomw.console.foxglove;

/**
 * The level of a {@code status} message, with its code on the wire: 0 info, 1 warning, 2 error
 * (the protocol's numbers; never the enum's order).
 */
public enum StatusLevel {
    /** 0. */
    INFO(0),
    /** 1. */
    WARNING(1),
    /** 2. */
    ERROR(2);

    private final int code;

    StatusLevel(int code) {
        this.code = code;
    }

    /** @return its number on the wire */
    public int code() {
        return code;
    }
}
