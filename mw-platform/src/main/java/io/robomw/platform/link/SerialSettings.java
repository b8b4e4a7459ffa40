package io.robomw.platform.link;

import java.util.Objects;

/**
 * Line settings of a serial port. On a pseudo-terminal they are accepted but have no effect: a pty
 * passes bytes at memory speed and never checks parity.
 *
 * @param baud     bits per second, positive
 * @param dataBits data bits per character, 5 to 8
 * @param parity   the parity bit
 * @param stopBits stop bits per character, 1 or 2
 */
public record SerialSettings(int baud, int dataBits, Parity parity, int stopBits) {

    /** The parity bit sent after the data bits. */
    public enum Parity {
        /** No parity bit. */
        NONE,
        /** The bit makes the count of ones odd (the LEGO RCX tower uses it). */
        ODD,
        /** The bit makes the count of ones even. */
        EVEN,
        /** The bit is always 1. */
        MARK,
        /** The bit is always 0. */
        SPACE
    }

    /** Checks every field and names the bad value. */
    public SerialSettings {
        if (baud <= 0) {
            throw new IllegalArgumentException("baud must be positive, baud=" + baud);
        }
        if (dataBits < 5 || dataBits > 8) {
            throw new IllegalArgumentException("dataBits must be 5 to 8, dataBits=" + dataBits);
        }
        Objects.requireNonNull(parity, "parity");
        if (stopBits != 1 && stopBits != 2) {
            throw new IllegalArgumentException("stopBits must be 1 or 2, stopBits=" + stopBits);
        }
    }

    /**
     * @param baud     bits per second
     * @param dataBits data bits, 5 to 8
     * @param parity   the parity bit
     * @param stopBits stop bits, 1 or 2
     * @return the settings, e.g. {@code of(9600, 8, NONE, 1)} for 9600 8N1
     */
    public static SerialSettings of(int baud, int dataBits, Parity parity, int stopBits) {
        return new SerialSettings(baud, dataBits, parity, stopBits);
    }

    /** @return the usual short form, e.g. {@code "9600 8N1"} or {@code "2400 8O1"} */
    @Override
    public String toString() {
        return baud + " " + dataBits + parity.name().charAt(0) + stopBits;
    }
}
