package io.robomw.agents.host;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

/**
 * What an agent host says of itself when asked ({@code DESCRIBE}): its name and address, its
 * robot, where its messaging node receives, and the other hosts it knows, so that agents can
 * address messages to a host by name and hosts learn of each other.
 *
 * <pre>
 * body = version:u8 (= 1)
 *        name:utf  address:utf  robot:utf ("" = none)
 *        messagingCount:u16  messaging:utf × messagingCount
 *        knownCount:u16      (name:utf address:utf) × knownCount
 * </pre>
 * {@code utf} is Java's modified UTF-8 with a 2-byte length ({@link DataOutputStream#writeUTF}),
 * numbers are big-endian. A body of another version, or with more than {@value #MAX_LIST}
 * entries in a list, is refused.
 *
 * @param name      the host's name
 * @param address   its address, {@code rmi://host:port/name}
 * @param robot     its robot's name, or "" when it has none
 * @param messaging the addresses its messaging node receives at; empty without messaging
 * @param known     other hosts it knows
 */
public record HostDescription(String name, String address, String robot, List<String> messaging, List<Known> known) {

    /** The body's format version. */
    public static final int VERSION = 1;
    /** The most entries a list of a description may have. */
    public static final int MAX_LIST = 1024;

    /**
     * A host another host knows of.
     *
     * @param name    its name
     * @param address its address
     */
    public record Known(String name, String address) {
        /** Checks the values. */
        public Known {
            Objects.requireNonNull(name, "name");
            Objects.requireNonNull(address, "address");
        }
    }

    /** Checks and copies. */
    public HostDescription {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(address, "address");
        Objects.requireNonNull(robot, "robot");
        messaging = List.copyOf(messaging.subList(0, Math.min(messaging.size(), MAX_LIST)));
        known = List.copyOf(known.subList(0, Math.min(known.size(), MAX_LIST)));
    }

    /** @return the body of a DESCRIBE reply */
    public byte[] encode() {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeByte(VERSION);
            out.writeUTF(name);
            out.writeUTF(address);
            out.writeUTF(robot);
            out.writeShort(messaging.size());
            for (String m : messaging) {
                out.writeUTF(m);
            }
            out.writeShort(known.size());
            for (Known k : known) {
                out.writeUTF(k.name());
                out.writeUTF(k.address());
            }
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * @param body a DESCRIBE reply's body
     * @param peer who sent it, for the message
     * @return the description
     * @throws IllegalArgumentException naming the peer and what is wrong
     */
    public static HostDescription decode(byte[] body, String peer) {
        try (DataInputStream in = new DataInputStream(new ByteArrayInputStream(body))) {
            int version = in.readUnsignedByte();
            if (version != VERSION) {
                throw new IllegalArgumentException(peer + " described itself in format version " + version + "; this host reads version " + VERSION);
            }
            String name = in.readUTF();
            String address = in.readUTF();
            String robot = in.readUTF();
            List<String> messaging = new ArrayList<>();
            int m = count(in, peer);
            for (int i = 0; i < m; i++) {
                messaging.add(in.readUTF());
            }
            List<Known> known = new ArrayList<>();
            int k = count(in, peer);
            for (int i = 0; i < k; i++) {
                known.add(new Known(in.readUTF(), in.readUTF()));
            }
            if (in.available() > 0) {
                throw new IllegalArgumentException(peer + " sent " + in.available() + " bytes after its description");
            }
            return new HostDescription(name, address, robot, messaging, known);
        } catch (IOException e) {
            throw new IllegalArgumentException(peer + " sent a description that ends early or is not modified UTF-8: " + e, e);
        }
    }

    private static int count(DataInputStream in, String peer) throws IOException {
        int n = in.readUnsignedShort();
        if (n > MAX_LIST) {
            throw new IllegalArgumentException(peer + " sent a list of " + n + " entries; at most " + MAX_LIST + " are read");
        }
        return n;
    }
}
