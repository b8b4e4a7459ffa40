package io.robomw.agents.host.code;

import io.robomw.agents.messaging.security.PayloadAllowList;
import io.robomw.api.Agent;
import io.robomw.api.Itinerary;
import io.robomw.api.Pose;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InvalidClassException;
import java.io.ObjectInputFilter;
import java.io.ObjectInputStream;
import java.io.ObjectOutputStream;
import java.io.ObjectStreamClass;
import java.io.Serializable;
import java.util.List;
import java.util.concurrent.atomic.AtomicReference;

/**
 * Turns agents and the values they carry into bytes and back. Reading goes through an
 * {@link ObjectInputFilter} that allows only the classes of the agent's own code (those its
 * {@link ArchiveClassLoader} defines, or those of the loader that sent it from home), the JDK value
 * types of {@link PayloadAllowList}, the agent API's own value types, and what the host's
 * operator adds; and that bounds the graph's depth, references, bytes and array lengths. A stream
 * that breaks a rule fails with {@link StateRejectedException} saying which rule, before the
 * offending object is made.
 */
public final class StateCodec {

    /** The agent API's serializable types, always allowed. */
    private static final List<String> API_TYPES = List.of(
            Agent.class.getName(), Itinerary.class.getName(), Itinerary.Stop.class.getName(), Itinerary.Visit.class.getName(),
            Itinerary.Outcome.class.getName(), Itinerary.UnreachablePolicy.class.getName(), Pose.class.getName(),
            io.robomw.api.SensorInfo.class.getName(), io.robomw.api.SensorType.class.getName(), io.robomw.api.Position.class.getName(),
            io.robomw.api.ReturnType.class.getName(), io.robomw.api.Quantity.class.getName(),
            "java.lang.invoke.SerializedLambda", "java.lang.Object", "java.util.Arrays$ArrayList");

    /** Deepest object graph accepted in agent state. */
    public static final int MAX_DEPTH = 64;
    /** Most object references in one agent's state. */
    public static final int MAX_REFERENCES = 1_000_000;

    private final PayloadAllowList allowList;
    private final long maxBytes;

    /**
     * @param extraAllowed class names the host's operator allows besides the agent's own classes
     * @param maxBytes     the largest state accepted, which also bounds every array's length
     */
    public StateCodec(List<String> extraAllowed, long maxBytes) {
        this.allowList = PayloadAllowList.jdkDefaults().withNames(API_TYPES).withNames(extraAllowed);
        this.maxBytes = maxBytes;
    }

    /** @return the largest state accepted, in bytes */
    public long maxBytes() {
        return maxBytes;
    }

    /**
     * @param value an agent or a value it carries
     * @return its serialized form
     * @throws IOException if something in it is not serializable (the message names the class)
     */
    public static byte[] write(Serializable value) throws IOException {
        return write(value, 512);
    }

    /**
     * Writes a value's serialized form to a stream (flushed, not closed).
     *
     * @param value an agent or a value it carries
     * @param to    where to write it
     * @throws IOException if something in it is not serializable (the message names the class), or the stream fails
     */
    public static void write(Serializable value, java.io.OutputStream to) throws IOException {
        ObjectOutputStream out = new ObjectOutputStream(to);
        out.writeObject(value);
        out.flush();
    }

    /**
     * @param value    an agent or a value it carries
     * @param expected about how many bytes it takes (its size last time): a buffer of that size
     *                 is not grown and copied over and over on the way to megabytes
     * @return its serialized form
     * @throws IOException if something in it is not serializable (the message names the class)
     */
    public static byte[] write(Serializable value, int expected) throws IOException {
        ByteArrayOutputStream bytes = new ByteArrayOutputStream(Math.max(512, expected + 256));
        try (ObjectOutputStream out = new ObjectOutputStream(bytes)) {
            out.writeObject(value);
        }
        return bytes.toByteArray();
    }

    /**
     * @param bytes     a serialized value
     * @param codeOwner the class loader of the agent's own code: its classes are allowed and resolved through it
     * @param type      what the value must be
     * @param <T>       that type
     * @return the value (may be {@code null})
     * @throws StateRejectedException if the stream breaks the filter's rules, is malformed, or is not a {@code type}
     */
    public <T> T read(byte[] bytes, ClassLoader codeOwner, Class<T> type) throws StateRejectedException {
        return read(bytes, 0, bytes.length, codeOwner, type);
    }

    /**
     * {@link #read(byte[], ClassLoader, Class)} from part of an array.
     *
     * @param bytes     holds a serialized value
     * @param offset    where it starts
     * @param length    its length
     * @param codeOwner the class loader of the agent's own code
     * @param type      what the value must be
     * @param <T>       that type
     * @return the value (may be {@code null})
     * @throws StateRejectedException if the stream breaks the filter's rules, is malformed, or is not a {@code type}
     */
    public <T> T read(byte[] bytes, int offset, int length, ClassLoader codeOwner, Class<T> type) throws StateRejectedException {
        if (length > maxBytes) {
            throw new StateRejectedException("state of " + length + " bytes is larger than the " + maxBytes + " allowed");
        }
        AtomicReference<String> why = new AtomicReference<>();
        ObjectInputFilter filter = info -> {
            if (info.depth() > MAX_DEPTH || info.references() > MAX_REFERENCES || info.streamBytes() > maxBytes || info.arrayLength() > maxBytes) {
                why.compareAndSet(null, "a limit was broken (depth " + info.depth() + " of " + MAX_DEPTH + ", references " + info.references()
                        + " of " + MAX_REFERENCES + ", bytes " + info.streamBytes() + " of " + maxBytes + ", array length " + info.arrayLength()
                        + " of " + maxBytes + ")");
                return ObjectInputFilter.Status.REJECTED;
            }
            Class<?> c = info.serialClass();
            if (c == null || ownedBy(c, codeOwner) || allowList.allows(c)) {
                return ObjectInputFilter.Status.ALLOWED;
            }
            why.compareAndSet(null, "class " + c.getName() + " is neither the agent's own code nor on the host's allow-list");
            return ObjectInputFilter.Status.REJECTED;
        };
        try (ObjectInputStream in = new ObjectInputStream(new ByteArrayInputStream(bytes, offset, length)) {
            @Override
            protected Class<?> resolveClass(ObjectStreamClass desc) throws IOException, ClassNotFoundException {
                return codeOwner instanceof ArchiveClassLoader archived ? archived.resolve(desc.getName()) : Class.forName(desc.getName(), false, codeOwner);
            }
        }) {
            in.setObjectInputFilter(filter);
            Object value = in.readObject();
            if (value != null && !type.isInstance(value)) {
                throw new StateRejectedException("expected a " + type.getName() + " but the state holds a " + (value == null ? "null" : value.getClass().getName()));
            }
            return type.cast(value);
        } catch (InvalidClassException e) {
            throw new StateRejectedException(why.get() != null ? why.get() : "invalid class: " + e.getMessage(), e);
        } catch (ClassNotFoundException e) {
            throw new StateRejectedException("class " + e.getMessage() + " is not in the agent's archive nor on the host's class path", e);
        } catch (IOException | RuntimeException e) {
            throw new StateRejectedException(why.get() != null ? why.get() : "malformed state: " + e, e);
        }
    }

    private static boolean ownedBy(Class<?> c, ClassLoader owner) {
        Class<?> base = c;
        while (base.isArray()) {
            base = base.getComponentType();
        }
        return !base.isPrimitive() && base.getClassLoader() == owner && owner != null && !(owner == ClassLoader.getPlatformClassLoader());
    }
}
