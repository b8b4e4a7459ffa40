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
import java.io.ObjectStreamConstants;
import java.io.StreamCorruptedException;
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

    /** The first two bytes of an agent's state in the compact form ({@link #writeCompact}): "RM". */
    public static final int COMPACT_MAGIC = 0x524D;
    /** The compact form's version, the two bytes after {@link #COMPACT_MAGIC}. */
    public static final int COMPACT_VERSION = 1;
    /** A pooled stream that wrote more than this is not pooled again (its handle tables grew with the state). */
    static final int POOL_MAX_BYTES = 16 * 1024;

    /** Deepest object graph accepted in agent state. */
    public static final int MAX_DEPTH = 64;
    /** Most object references in one agent's state. */
    public static final int MAX_REFERENCES = 1_000_000;

    /**
     * A form of an agent's state on the way to another host ({@link #writeAgent}): the compact one
     * to hosts that read it (their sessions are of agent protocol version 5), the standard one to
     * the others.
     */
    public enum Form {
        /** Java serialization's own stream ({@code ACED 0005}): what every host reads, builds before the compact form too. */
        STANDARD,
        /** The compact form ({@link #writeCompact}): hosts of builds before it refuse it. */
        COMPACT
    }

    private final PayloadAllowList allowList;
    private final long maxBytes;
    private final Form form;

    /**
     * A codec that reads both forms and writes agents in the compact form to hosts that read it.
     *
     * @param extraAllowed class names the host's operator allows besides the agent's own classes
     * @param maxBytes     the largest state accepted, which also bounds every array's length
     */
    public StateCodec(List<String> extraAllowed, long maxBytes) {
        this(extraAllowed, maxBytes, Form.COMPACT);
    }

    /**
     * @param extraAllowed class names the host's operator allows besides the agent's own classes
     * @param maxBytes     the largest state accepted, which also bounds every array's length
     * @param form         {@link Form#COMPACT}; {@link Form#STANDARD} for a codec as builds before the compact form
     *                     had (tests of mixed versions): it writes only the standard form and refuses
     *                     the compact one ("invalid stream header"), as they did
     */
    public StateCodec(List<String> extraAllowed, long maxBytes, Form form) {
        this.allowList = PayloadAllowList.jdkDefaults().withNames(API_TYPES).withNames(extraAllowed);
        this.maxBytes = maxBytes;
        this.form = java.util.Objects.requireNonNull(form);
    }

    /**
     * Writes an agent on its way to another host.
     *
     * @param agent an agent
     * @param to    where to write it
     * @param reads the form the next host reads: {@link Form#STANDARD} for a host of a build before
     *              the compact form (its session is of a protocol version before 5)
     * @throws IOException if something in it is not serializable (the message names the class), or the stream fails
     */
    public void writeAgent(Serializable agent, java.io.OutputStream to, Form reads) throws IOException {
        if (form == Form.COMPACT && reads == Form.COMPACT) {
            writeCompact(agent, to);
        } else {
            write(agent, to);
        }
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
     * Writes an agent's state in the compact form to a stream (flushed, not closed): Java
     * serialization's stream, except that it starts with {@link #COMPACT_MAGIC} {@link #COMPACT_VERSION}
     * instead of {@code ACED 0005}, then a reset ({@code TC_RESET}), and that each class descriptor is
     * only the class's name (modified UTF-8, as {@code writeUTF}) and its {@linkplain #fingerprint
     * fingerprint} (8 bytes) instead of its serialVersionUID, flags and every field's name and type.
     * An agent's classes travel in its archive, so the reader has the very same classes; the
     * fingerprint proves it (a class that differs is refused naming it). On a hop of the
     * many-agents benchmark's agent the descriptors were most of what reading its state allocated.
     * A host older than this form refuses such a state ("invalid stream header: 524D0001").
     *
     * <p>The stream objects are pooled (a few of this codec's, that is of its host's, shared by its threads; one that
     * wrote more than {@link #POOL_MAX_BYTES} is dropped, so the pool never keeps a large state's handle tables).
     *
     * @param value an agent
     * @param to    where to write it
     * @throws IOException if something in it is not serializable (the message names the class), or the stream fails
     */
    public void writeCompact(Serializable value, java.io.OutputStream to) throws IOException {
        CompactOut out = streams.poll();
        if (out == null) {
            out = new CompactOut(new Sink());
        }
        boolean reusable = false;
        try {
            out.sink.start(to);
            to.write(COMPACT_HEADER);
            out.reset();
            out.writeObject(value);
            out.flush();
            reusable = out.sink.written <= POOL_MAX_BYTES;
        } finally {
            out.sink.start(null);
            if (reusable) {
                streams.offer(out);
            }
        }
    }

    /**
     * @param c a class
     * @return the first 8 bytes (big-endian) of the SHA-256 of the class's standard serialization
     *         descriptor (name, serialVersionUID, flags, fields, and its serializable superclasses'
     *         descriptors), computed once per class
     */
    public static long fingerprint(Class<?> c) {
        return FINGERPRINTS.get(c);
    }

    private static final ClassValue<Long> FINGERPRINTS = new ClassValue<>() {
        @Override
        protected Long computeValue(Class<?> c) {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream(256);
            try (ObjectOutputStream o = new ObjectOutputStream(bytes)) {
                o.writeObject(ObjectStreamClass.lookupAny(c));
            } catch (IOException e) {
                throw new java.io.UncheckedIOException("cannot write the serialization descriptor of " + c.getName(), e);
            }
            try {
                byte[] d = java.security.MessageDigest.getInstance("SHA-256").digest(bytes.toByteArray());
                return java.nio.ByteBuffer.wrap(d).getLong();
            } catch (java.security.NoSuchAlgorithmException e) {
                throw new IllegalStateException("SHA-256 is missing from this JDK", e);
            }
        }
    };

    /** The pooled streams of {@link #writeCompact}: at most a few, whichever of the host's threads writes. */
    private final java.util.concurrent.ArrayBlockingQueue<CompactOut> streams = new java.util.concurrent.ArrayBlockingQueue<>(8);
    private static final byte[] COMPACT_HEADER = {(byte) (COMPACT_MAGIC >>> 8), (byte) COMPACT_MAGIC, (byte) (COMPACT_VERSION >>> 8), (byte) COMPACT_VERSION};

    /** Where a pooled {@link CompactOut} writes: the stream of the value being written, and how much went to it. */
    private static final class Sink extends java.io.OutputStream {
        private java.io.OutputStream to;
        private long written;

        void start(java.io.OutputStream target) {
            to = target;
            written = 0;
        }

        private java.io.OutputStream to() throws IOException {
            if (to == null) {
                throw new IOException("a pooled state stream written outside writeCompact");
            }
            return to;
        }

        @Override
        public void write(int b) throws IOException {
            to().write(b);
            written++;
        }

        @Override
        public void write(byte[] b, int off, int len) throws IOException {
            to().write(b, off, len);
            written += len;
        }

        @Override
        public void flush() throws IOException {
            if (to != null) {
                to.flush();
            }
        }
    }

    /** Java serialization with compact class descriptors and no header of its own ({@link #writeCompact} writes it). */
    private static final class CompactOut extends ObjectOutputStream {
        private final Sink sink;

        CompactOut(Sink sink) throws IOException {
            super(sink);
            this.sink = sink;
        }

        @Override
        protected void writeStreamHeader() {
            // each value's header is written by writeCompact
        }

        @Override
        protected void writeClassDescriptor(ObjectStreamClass desc) throws IOException {
            writeUTF(desc.getName());
            writeLong(fingerprint(desc.forClass()));
        }
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
            if (c == null || allowed(c, codeOwner)) {
                return ObjectInputFilter.Status.ALLOWED;
            }
            why.compareAndSet(null, notAllowed(c));
            return ObjectInputFilter.Status.REJECTED;
        };
        try (StateIn in = new StateIn(new ByteArrayInputStream(bytes, offset, length), codeOwner, why)) {
            in.setObjectInputFilter(filter);
            Object value = in.readObject();
            if (value != null && !type.isInstance(value)) {
                throw new StateRejectedException("expected a " + type.getName() + " but the state holds a " + (value == null ? "null" : value.getClass().getName()));
            }
            return type.cast(value);
        } catch (InvalidClassException e) {
            throw new StateRejectedException(why.get() != null ? why.get() : "invalid class: " + e.getMessage(), e);
        } catch (ClassNotFoundException e) {
            throw new StateRejectedException(missing(e.getMessage()), e);
        } catch (IOException | RuntimeException e) {
            throw new StateRejectedException(why.get() != null ? why.get() : "malformed state: " + e, e);
        }
    }

    private static String missing(String className) {
        return "class " + className + " is not in the agent's archive nor on the host's class path";
    }

    private static String notAllowed(Class<?> c) {
        return "class " + c.getName() + " is neither the agent's own code nor on the host's allow-list";
    }

    private boolean allowed(Class<?> c, ClassLoader codeOwner) {
        return ownedBy(c, codeOwner) || allowList.allows(c);
    }

    /**
     * Reads either form of state: Java serialization's own ({@code ACED 0005}: what {@link #write}
     * makes, and what every host wrote before the compact form) or the compact one
     * ({@link #COMPACT_MAGIC} {@link #COMPACT_VERSION}: {@link #writeCompact}). A compact class
     * descriptor is checked against the allow-list before anything about its class is looked up
     * (looking up a class's serialVersionUID initializes it), then against this host's class by
     * its {@linkplain #fingerprint fingerprint}.
     */
    private final class StateIn extends ObjectInputStream {
        /** Set by {@link #readStreamHeader} during the super constructor: no initializer, or it would be reset after it. */
        private boolean compact;
        private final ClassLoader codeOwner;
        private final AtomicReference<String> why;

        StateIn(java.io.InputStream in, ClassLoader codeOwner, AtomicReference<String> why) throws IOException {
            super(in);
            this.codeOwner = codeOwner;
            this.why = why;
        }

        @Override
        protected void readStreamHeader() throws IOException {
            int magic = readUnsignedShort();
            int version = readUnsignedShort();
            if (magic == (ObjectStreamConstants.STREAM_MAGIC & 0xFFFF) && version == ObjectStreamConstants.STREAM_VERSION) {
                return;
            }
            if (magic == COMPACT_MAGIC && version == COMPACT_VERSION && form == Form.COMPACT) {
                compact = true;
                return;
            }
            if (form == Form.STANDARD) {
                // as a build before the compact form read it (tests of mixed versions)
                throw new StreamCorruptedException(String.format("invalid stream header: %04X%04X", magic, version));
            }
            throw new StreamCorruptedException(String.format("state stream header %04x %04x is neither Java serialization's (aced 0005) nor"
                    + " this host's compact form (%04x %04x): written by a newer host?", magic, version, COMPACT_MAGIC, COMPACT_VERSION));
        }

        @Override
        protected ObjectStreamClass readClassDescriptor() throws IOException, ClassNotFoundException {
            if (!compact) {
                return super.readClassDescriptor();
            }
            String name = readUTF();
            long fingerprint = readLong();
            Class<?> c;
            try {
                c = resolve(name);
            } catch (ClassNotFoundException e) {
                why.compareAndSet(null, missing(name));
                throw new InvalidClassException(name, "not found");
            }
            if (!allowed(c, codeOwner)) {
                why.compareAndSet(null, notAllowed(c));
                throw new InvalidClassException(name, "not allowed");
            }
            if (fingerprint(c) != fingerprint) {
                why.compareAndSet(null, "class " + name + " at this host differs from the one the state was written with"
                        + " (its serialVersionUID, its fields or its serialization methods)");
                throw new InvalidClassException(name, "differs");
            }
            return ObjectStreamClass.lookupAny(c);
        }

        @Override
        protected Class<?> resolveClass(ObjectStreamClass desc) throws IOException, ClassNotFoundException {
            // a compact descriptor is this host's own, of the class just resolved and checked
            Class<?> c = compact ? desc.forClass() : null;
            return c != null ? c : resolve(desc.getName());
        }

        private Class<?> resolve(String name) throws ClassNotFoundException {
            return codeOwner instanceof ArchiveClassLoader archived ? archived.resolve(name) : Class.forName(name, false, codeOwner);
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
