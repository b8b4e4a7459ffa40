package io.robomw.sim.emulator;

import java.io.IOException;

/**
 * How a brick's telegrams are delimited on its link: by a length prefix (NXT and EV3 over
 * Bluetooth serial), by the command byte (fischertechnik Intelligent Interface), by a message
 * identifier (fischertechnik TXT).
 */
public interface Framing {

    /**
     * Reads one telegram.
     *
     * @param in reads exactly n bytes (waiting for the first one as long as the emulator runs, then
     *           at most a frame deadline); returns {@code null} if they did not come
     * @return the telegram, or {@code null} when the input did not make one (it is then dropped
     *         and counted by the caller)
     * @throws IOException if the link failed
     * @throws MalformedFrameException if the input cannot be a telegram (the caller logs it, drops
     *                                 it and drains the line)
     */
    byte[] read(Reader in) throws IOException;

    /**
     * @param reply a reply as {@link BrickEmulator#handle} returned it
     * @return the bytes to send
     */
    byte[] encode(byte[] reply);

    /** Reads exactly n bytes. */
    @FunctionalInterface
    interface Reader {
        /**
         * @param n how many
         * @return them, or {@code null} if they did not come in time or the emulator stopped
         * @throws IOException if the link failed
         */
        byte[] readExactly(int n) throws IOException;
    }

    /** Input that cannot be a telegram. */
    final class MalformedFrameException extends IOException {
        private static final long serialVersionUID = 1L;

        /**
         * @param message what is wrong
         */
        public MalformedFrameException(String message) {
            super(message);
        }
    }

    /**
     * @param maxLength the longest telegram after the prefix
     * @return the 2-byte little-endian length prefix framing
     */
    static Framing lengthPrefixed(int maxLength) {
        return new Framing() {
            @Override
            public byte[] read(Reader in) throws IOException {
                byte[] header = in.readExactly(2);
                if (header == null) {
                    return null;
                }
                int length = (header[0] & 0xFF) | (header[1] & 0xFF) << 8;
                if (length == 0 || length > maxLength) {
                    throw new MalformedFrameException("frame length " + length + " outside 1.." + maxLength);
                }
                return in.readExactly(length);
            }

            @Override
            public byte[] encode(byte[] reply) {
                byte[] out = new byte[reply.length + 2];
                out[0] = (byte) reply.length;
                out[1] = (byte) (reply.length >> 8);
                System.arraycopy(reply, 0, out, 2, reply.length);
                return out;
            }
        };
    }
}
