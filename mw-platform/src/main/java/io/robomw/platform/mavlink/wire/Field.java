package io.robomw.platform.mavlink.wire;

import java.util.Objects;

/**
 * One field of a {@link MessageType}: its name, type, array length and where it sits in the
 * payload on the wire. Fields are made by {@link MessageType#define} only; a {@link Payload} reads
 * and writes a field of its own message type and refuses any other.
 */
public final class Field {

    private final MessageType message;
    private final String name;
    private final FieldType type;
    private final int arrayLength;
    private final boolean extension;
    private final int offset;

    Field(MessageType message, String name, FieldType type, int arrayLength, boolean extension, int offset) {
        this.message = Objects.requireNonNull(message, "message");
        this.name = Objects.requireNonNull(name, "name");
        this.type = Objects.requireNonNull(type, "type");
        this.arrayLength = arrayLength;
        this.extension = extension;
        this.offset = offset;
    }

    /** @return the message type it belongs to */
    public MessageType message() {
        return message;
    }

    /** @return its name, as in the message definition ({@code custom_mode}) */
    public String name() {
        return name;
    }

    /** @return its type (for an array, the element's) */
    public FieldType type() {
        return type;
    }

    /** @return the number of elements of an array field; 0 for a single value */
    public int arrayLength() {
        return arrayLength;
    }

    /** @return whether it is an extension field (after {@code <extensions/>}: not reordered, may be absent) */
    public boolean extension() {
        return extension;
    }

    /** @return its first byte's offset in the payload on the wire */
    public int offset() {
        return offset;
    }

    /** @return its bytes on the wire */
    public int size() {
        return type.size() * Math.max(1, arrayLength);
    }

    @Override
    public String toString() {
        return message.name() + "." + name;
    }
}
