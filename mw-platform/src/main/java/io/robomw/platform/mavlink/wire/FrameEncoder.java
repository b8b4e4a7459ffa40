package io.robomw.platform.mavlink.wire;

import java.util.Objects;

/**
 * Makes the MAVLink 2 frames one sender (a system and component id) sends: its sequence number
 * counts up by one per frame and wraps at 256; each payload is cut of its trailing zero bytes; with
 * a {@link Signer} every frame is signed. Thread-safe (frames from several threads get distinct
 * sequence numbers and increasing signature timestamps).
 */
public final class FrameEncoder {

    private final int systemId;
    private final int componentId;
    private volatile Signer signer;
    private int sequence;

    /**
     * @param systemId    the sender's system id, 1-255 (a ground station: 255 or 245, as MAVSDK's)
     * @param componentId the sender's component id, 0-255 (an autopilot: 1; a ground station: 190)
     */
    public FrameEncoder(int systemId, int componentId) {
        if (systemId < 1 || systemId > 255 || componentId < 0 || componentId > 255) {
            throw new IllegalArgumentException("a MAVLink system id is 1-255 and a component id 0-255, got " + systemId + "/" + componentId);
        }
        this.systemId = systemId;
        this.componentId = componentId;
    }

    /** @return the sender's system id */
    public int systemId() {
        return systemId;
    }

    /** @return the sender's component id */
    public int componentId() {
        return componentId;
    }

    /**
     * @param signer signs every frame from now on; {@code null} sends them unsigned
     * @return this
     */
    public FrameEncoder signWith(Signer signer) {
        this.signer = signer;
        return this;
    }

    /** @return the signer, or {@code null} when frames go unsigned */
    public Signer signer() {
        return signer;
    }

    /**
     * @param payload a message
     * @return its frame
     */
    public byte[] encode(Payload payload) {
        return encode(payload, systemId, componentId);
    }

    /**
     * Encodes a frame as if from another sender (a router's forward, or a test's): its own
     * sequence number still counts.
     *
     * @param payload     a message
     * @param fromSystem  the system id written in the frame
     * @param fromComponent the component id written in the frame
     * @return its frame
     */
    public synchronized byte[] encode(Payload payload, int fromSystem, int fromComponent) {
        Objects.requireNonNull(payload, "payload");
        byte[] wire = payload.toWire();
        Signer s = signer;
        int unsigned = Framing.HEADER_V2 + wire.length + Framing.CHECKSUM;
        byte[] f = new byte[unsigned + (s == null ? 0 : Framing.SIGNATURE_BLOCK)];
        int id = payload.type().id();
        f[0] = (byte) Framing.STX_V2;
        f[Framing.LEN] = (byte) wire.length;
        f[Framing.INCOMPAT_FLAGS] = (byte) (s == null ? 0 : Framing.INCOMPAT_SIGNED);
        f[Framing.COMPAT_FLAGS] = 0;
        f[Framing.SEQ] = (byte) sequence;
        f[Framing.SYSID] = (byte) fromSystem;
        f[Framing.COMPID] = (byte) fromComponent;
        f[Framing.MSGID] = (byte) id;
        f[Framing.MSGID + 1] = (byte) (id >>> 8);
        f[Framing.MSGID + 2] = (byte) (id >>> 16);
        System.arraycopy(wire, 0, f, Framing.HEADER_V2, wire.length);
        int crc = Crc.accumulate(Crc.INITIAL, f, 1, Framing.HEADER_V2 - 1 + wire.length);
        crc = Crc.accumulate(crc, payload.type().crcExtra());
        f[Framing.HEADER_V2 + wire.length] = (byte) crc;
        f[Framing.HEADER_V2 + wire.length + 1] = (byte) (crc >>> 8);
        if (s != null) {
            s.sign(f, unsigned);
        }
        sequence = (sequence + 1) & 0xFF;
        return f;
    }
}
