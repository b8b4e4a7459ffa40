package io.robomw.console.rosbridge.protocol;

/**
 * A client's connection as the {@link Outbox} sees it: frames go out in order, a few at a time,
 * and each send says when it is done, so the outbox knows when the client has taken a frame (and
 * keeps the rest, bounded, until it has).
 */
public interface Transport {

    /**
     * Sends a text frame.
     *
     * @param text the frame
     * @param done called once the frame is written, or failed (the connection then closes); may
     *             be called before this method returns
     */
    void sendText(String text, Runnable done);

    /**
     * Sends a binary frame ({@code compression: cbor}).
     *
     * @param data the frame
     * @param done as for {@link #sendText}
     */
    void sendBinary(byte[] data, Runnable done);

    /**
     * Closes the connection.
     *
     * @param code   the WebSocket close code
     * @param reason why, for the client
     */
    void close(int code, String reason);
}
