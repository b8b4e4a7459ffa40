package io.robomw.agents.net;

/**
 * A constant that travels (or is stored) as an explicit code, never as its position in its enum.
 * The code is written once, in the constant's constructor; {@link WireCodes} builds the table that
 * reads it back.
 */
public interface WireCode {

    /** @return the constant's code on the wire or on disk */
    int code();
}
