package io.robomw.console.foxglove;

import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.util.Arrays;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;

/**
 * The Foxglove WebSocket protocol's binary frames (data only; everything else is JSON text), all
 * integers little-endian:
 *
 * <pre>
 * server to client
 *   MESSAGE_DATA  0x01 | u32 subscription id | u64 log time, ns since the Unix epoch | payload (the message, JSON here)
 *   TIME          0x02 | u64 the server's time, ns since the Unix epoch
 *
 * client to server
 *   MESSAGE_DATA  0x01 | u32 client channel id (from the client's advertise) | payload
 *   SERVICE_CALL_REQUEST 0x02 ... and PLAYBACK_CONTROL_REQUEST 0x03 ...: known, not served here
 *                 (RoboMW offers no services and no playback control)
 * </pre>
 *
 * <table>
 *   <caption>opcodes</caption>
 *   <tr><th>direction</th><th>code</th><th>frame</th></tr>
 *   <tr><td>server</td><td>0x01</td><td>{@link #SERVER_MESSAGE_DATA}</td></tr>
 *   <tr><td>server</td><td>0x02</td><td>{@link #SERVER_TIME}</td></tr>
 *   <tr><td>client</td><td>0x01</td><td>{@link ClientOpcode#MESSAGE_DATA}</td></tr>
 *   <tr><td>client</td><td>0x02</td><td>{@link ClientOpcode#SERVICE_CALL_REQUEST}</td></tr>
 *   <tr><td>client</td><td>0x03</td><td>{@link ClientOpcode#PLAYBACK_CONTROL_REQUEST}</td></tr>
 * </table>
 *
 * From the legacy specification (foxglove/ws-protocol {@code docs/spec.md}) and the Foxglove SDK
 * 0.30.3, whose server sends and takes these bytes. Stateless.
 */
public final class BinaryFrames {

    /** Server opcode of a message on a subscription. */
    public static final byte SERVER_MESSAGE_DATA = 0x01;
    /** Server opcode of the server's time (the {@code time} capability). */
    public static final byte SERVER_TIME = 0x02;
    /** Offset of the subscription id in a server MESSAGE_DATA frame. */
    static final int SUBSCRIPTION_OFFSET = 1;
    /** Offset of the log time in a server MESSAGE_DATA frame. */
    static final int LOG_TIME_OFFSET = 5;
    /** Length of a server MESSAGE_DATA frame's header; the payload follows. */
    public static final int MESSAGE_DATA_HEADER = 13;
    /** Length of a TIME frame. */
    public static final int TIME_LENGTH = 9;
    /** Offset of the channel id in a client MESSAGE_DATA frame. */
    static final int CLIENT_CHANNEL_OFFSET = 1;
    /** Length of a client MESSAGE_DATA frame's header; the payload follows. */
    public static final int CLIENT_MESSAGE_DATA_HEADER = 5;
    /** The largest u32, the range of ids. */
    public static final long U32_MAX = 0xFFFF_FFFFL;

    /** The opcodes a client may send in a binary frame. */
    public enum ClientOpcode {
        /** 0x01: a message on a channel the client advertised. */
        MESSAGE_DATA(0x01),
        /** 0x02: a service call (RoboMW offers no services). */
        SERVICE_CALL_REQUEST(0x02),
        /** 0x03: a playback control request (RoboMW offers no playback control). */
        PLAYBACK_CONTROL_REQUEST(0x03);

        private static final Map<Integer, ClientOpcode> BY_CODE = Arrays.stream(values())
                .collect(Collectors.toUnmodifiableMap(ClientOpcode::code, Function.identity()));
        private final int code;

        ClientOpcode(int code) {
            this.code = code;
        }

        /** @return its byte on the wire */
        public int code() {
            return code;
        }

        /**
         * @param code a frame's first byte, 0-255
         * @return its opcode
         * @throws ClientRequest.BadRequest naming the code, if it is none
         */
        public static ClientOpcode fromCode(int code) throws ClientRequest.BadRequest {
            ClientOpcode op = BY_CODE.get(code);
            if (op == null) {
                throw new ClientRequest.BadRequest(String.format("Unknown binary opcode %d (0x%02x): a client sends 0x01 MESSAGE_DATA", code, code));
            }
            return op;
        }
    }

    /**
     * A client's MESSAGE_DATA frame.
     *
     * @param channelId the client channel it is on (u32)
     * @param payload   the message
     */
    public record ClientMessage(long channelId, byte[] payload) {
    }

    private BinaryFrames() {
    }

    /**
     * @param subscriptionId the client's id of its subscription (u32)
     * @param logTimeNanos   the message's log time, ns since the Unix epoch
     * @param payload        the message
     * @return a server MESSAGE_DATA frame, ready to send
     */
    public static ByteBuffer messageData(long subscriptionId, long logTimeNanos, byte[] payload) {
        ByteBuffer b = ByteBuffer.allocate(MESSAGE_DATA_HEADER + payload.length).order(ByteOrder.LITTLE_ENDIAN);
        b.put(SERVER_MESSAGE_DATA).putInt((int) requireU32(subscriptionId, "subscription id")).putLong(logTimeNanos).put(payload);
        return b.flip();
    }

    /**
     * @param timeNanos the server's time, ns since the Unix epoch
     * @return a TIME frame, ready to send
     */
    public static ByteBuffer time(long timeNanos) {
        return ByteBuffer.allocate(TIME_LENGTH).order(ByteOrder.LITTLE_ENDIAN).put(SERVER_TIME).putLong(timeNanos).flip();
    }

    /**
     * Reads a client's binary frame.
     *
     * @param frame the frame (read from its position; the buffer is not changed)
     * @return the message it carries
     * @throws ClientRequest.BadRequest saying what is wrong (empty, an unknown or unserved opcode, too short), in the words the SDK uses
     */
    public static ClientMessage parseClient(ByteBuffer frame) throws ClientRequest.BadRequest {
        ByteBuffer b = frame.slice().order(ByteOrder.LITTLE_ENDIAN);
        if (!b.hasRemaining()) {
            throw new ClientRequest.BadRequest("Empty binary message: a binary frame starts with its opcode, 0x01 for MESSAGE_DATA");
        }
        ClientOpcode op = ClientOpcode.fromCode(b.get(0) & 0xFF);
        switch (op) {
            case MESSAGE_DATA -> {
                if (b.remaining() < CLIENT_MESSAGE_DATA_HEADER) {
                    throw new ClientRequest.BadRequest("Buffer too short: a MESSAGE_DATA frame is 0x01, a u32 channel id and the message ("
                            + CLIENT_MESSAGE_DATA_HEADER + " bytes at least), got " + b.remaining());
                }
                long channel = Integer.toUnsignedLong(b.getInt(CLIENT_CHANNEL_OFFSET));
                byte[] payload = new byte[b.remaining() - CLIENT_MESSAGE_DATA_HEADER];
                b.get(CLIENT_MESSAGE_DATA_HEADER, payload);
                return new ClientMessage(channel, payload);
            }
            case SERVICE_CALL_REQUEST -> throw new ClientRequest.BadRequest("Server does not support services");
            case PLAYBACK_CONTROL_REQUEST -> throw new ClientRequest.BadRequest("Server does not support playback control capability");
            default -> throw new IllegalStateException("opcode " + op + " has no case");
        }
    }

    static long requireU32(long value, String what) {
        if (value < 0 || value > U32_MAX) {
            throw new IllegalArgumentException(what + " must be a u32 (0 to " + U32_MAX + "), got " + value);
        }
        return value;
    }
}
