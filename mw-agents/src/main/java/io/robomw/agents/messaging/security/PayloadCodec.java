package io.robomw.agents.messaging.security;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InvalidClassException;
import java.io.NotSerializableException;
import java.io.ObjectInputStream;
import java.io.ObjectOutputStream;
import java.io.ObjectStreamClass;
import java.io.Serializable;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.nio.charset.StandardCharsets;

/**
 * Turns payloads into bytes and back. Plain values have their own compact encodings and are
 * never deserialized as objects: {@code null}, {@code byte[]}, {@code String}, {@code Integer},
 * {@code Long}, {@code Double}, {@code Float}, {@code Boolean}. Every other payload uses Java
 * serialization and is read back only through the node's {@link PayloadAllowList} filter.
 *
 * <p>Thread-safe.
 */
public final class PayloadCodec {

    /** Payload type codes, as in the frame's PAYLOAD TYPE byte. */
    public static final int NULL = 0;
    public static final int BYTES = 1;
    public static final int STRING = 2;
    public static final int INTEGER = 3;
    public static final int LONG = 4;
    public static final int DOUBLE = 5;
    public static final int FLOAT = 6;
    public static final int BOOLEAN = 7;
    public static final int SERIALIZED = 127;

    private static final byte[] EMPTY = new byte[0];

    private final PayloadAllowList allowList;
    private final ClassLoader classLoader;

    /**
     * @param allowList   the classes objects may contain
     * @param classLoader where payload classes are loaded from
     */
    public PayloadCodec(PayloadAllowList allowList, ClassLoader classLoader) {
        this.allowList = allowList;
        this.classLoader = classLoader;
    }

    /**
     * An encoded payload.
     *
     * @param type  its type code
     * @param bytes its bytes
     */
    public record Encoded(int type, byte[] bytes) {
    }

    /**
     * @param payload a payload, or {@code null}
     * @return its encoding
     * @throws IllegalArgumentException if it cannot be serialized (a field is not serializable)
     */
    public Encoded encode(Serializable payload) {
        if (payload == null) {
            return new Encoded(NULL, EMPTY);
        }
        if (payload instanceof byte[] bytes) {
            return new Encoded(BYTES, bytes);
        }
        if (payload instanceof String s) {
            return new Encoded(STRING, s.getBytes(StandardCharsets.UTF_8));
        }
        if (payload instanceof Integer i) {
            return new Encoded(INTEGER, ByteBuffer.allocate(4).order(ByteOrder.BIG_ENDIAN).putInt(i).array());
        }
        if (payload instanceof Long l) {
            return new Encoded(LONG, ByteBuffer.allocate(8).order(ByteOrder.BIG_ENDIAN).putLong(l).array());
        }
        if (payload instanceof Double d) {
            return new Encoded(DOUBLE, ByteBuffer.allocate(8).order(ByteOrder.BIG_ENDIAN).putDouble(d).array());
        }
        if (payload instanceof Float f) {
            return new Encoded(FLOAT, ByteBuffer.allocate(4).order(ByteOrder.BIG_ENDIAN).putFloat(f).array());
        }
        if (payload instanceof Boolean b) {
            return new Encoded(BOOLEAN, new byte[] {(byte) (b ? 1 : 0)});
        }
        ByteArrayOutputStream bytes = new ByteArrayOutputStream(256);
        try (ObjectOutputStream out = new ObjectOutputStream(bytes)) {
            out.writeObject(payload);
        } catch (NotSerializableException e) {
            throw new IllegalArgumentException("payload " + payload.getClass().getName() + " cannot be serialized: "
                    + e.getMessage() + " is not Serializable", e);
        } catch (IOException e) {
            throw new IllegalArgumentException("payload " + payload.getClass().getName() + " cannot be serialized: " + e, e);
        }
        return new Encoded(SERIALIZED, bytes.toByteArray());
    }

    /**
     * @param type  the payload type code
     * @param bytes the encoded payload
     * @return the payload
     * @throws PayloadRejectedException if an object's class is not allowed, a limit was broken, or the bytes are not a valid encoding
     */
    public Serializable decode(int type, byte[] bytes) throws PayloadRejectedException {
        ByteBuffer in = ByteBuffer.wrap(bytes).order(ByteOrder.BIG_ENDIAN);
        switch (type) {
            case NULL:
                return null;
            case BYTES:
                return bytes;
            case STRING:
                return new String(bytes, StandardCharsets.UTF_8);
            case INTEGER:
                return fixed(bytes, 4) ? in.getInt() : bad(type, bytes);
            case LONG:
                return fixed(bytes, 8) ? in.getLong() : bad(type, bytes);
            case DOUBLE:
                return fixed(bytes, 8) ? in.getDouble() : bad(type, bytes);
            case FLOAT:
                return fixed(bytes, 4) ? in.getFloat() : bad(type, bytes);
            case BOOLEAN:
                return fixed(bytes, 1) ? bytes[0] != 0 : bad(type, bytes);
            case SERIALIZED:
                return deserialize(bytes);
            default:
                throw new PayloadRejectedException("unknown payload type code " + type + " (known: 0-7 and 127)", null);
        }
    }

    private Serializable deserialize(byte[] bytes) throws PayloadRejectedException {
        String[] rejected = new String[1];
        try (ObjectInputStream in = new LoaderObjectInputStream(new ByteArrayInputStream(bytes), classLoader)) {
            in.setObjectInputFilter(allowList.filter(bytes.length, why -> rejected[0] = why));
            Object o = in.readObject();
            if (!(o instanceof Serializable s)) {
                throw new PayloadRejectedException("payload of class " + o.getClass().getName() + " is not Serializable", null);
            }
            return s;
        } catch (InvalidClassException e) {
            throw new PayloadRejectedException("payload rejected: " + (rejected[0] != null ? rejected[0] : e.getMessage())
                    + " (the receiver allows application types with MessagingSettings.allowPayloadTypes)", e);
        } catch (IOException | ClassNotFoundException | RuntimeException e) {
            throw new PayloadRejectedException("payload cannot be read: " + e, e);
        }
    }

    private static boolean fixed(byte[] bytes, int length) {
        return bytes.length == length;
    }

    private static Serializable bad(int type, byte[] bytes) throws PayloadRejectedException {
        throw new PayloadRejectedException("payload type " + type + " with " + bytes.length + " bytes is not a valid encoding", null);
    }

    /** Resolves classes through the node's class loader rather than the caller's. */
    private static final class LoaderObjectInputStream extends ObjectInputStream {
        private final ClassLoader loader;

        LoaderObjectInputStream(java.io.InputStream in, ClassLoader loader) throws IOException {
            super(in);
            this.loader = loader;
        }

        @Override
        protected Class<?> resolveClass(ObjectStreamClass desc) throws IOException, ClassNotFoundException {
            try {
                return Class.forName(desc.getName(), false, loader);
            } catch (ClassNotFoundException e) {
                return super.resolveClass(desc);
            }
        }
    }
}
