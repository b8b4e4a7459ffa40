package io.robomw.platform.mavlink.wire;

import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Collections;
import java.util.Comparator;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * One MAVLink message as its definition gives it: name, id, CRC_EXTRA and fields, and the layout
 * its fields take on the wire (mavlink.io/en/guide/serialization.html):
 * <ul>
 *   <li>the fields before {@code <extensions/>} are sent sorted by the size of their type, largest
 *   first (a stable sort: fields of one size keep their declared order; an array sorts by its
 *   element's size);</li>
 *   <li>extension fields follow in their declared order, and a sender that does not know them
 *   leaves them out;</li>
 *   <li>the CRC_EXTRA byte, accumulated into every frame's checksum, is a checksum of the name and
 *   of the non-extension fields' types and names in wire order ({@link #computedCrcExtra}), so two
 *   ends that disagree on a message's layout reject each other's frames.</li>
 * </ul>
 * Immutable. The dialect of messages RoboMW uses is {@link Messages}.
 */
public final class MessageType {

    /** The marker between ordinary and extension fields in {@link #define}, as {@code <extensions/>} in the XML. */
    public static final String EXTENSIONS = "<extensions/>";
    /** The largest message id (24 bits in MAVLink 2). */
    public static final int MAX_ID = 0xFF_FFFF;

    private static final Pattern FIELD = Pattern.compile("([a-z0-9_]+)(?:\\[(\\d+)])? ([a-z_][a-z0-9_]*)");

    private final String name;
    private final int id;
    private final int crcExtra;
    private final List<Field> declared;
    private final List<Field> wireOrder;
    private final Map<String, Field> byName;
    private final int baseLength;
    private final int maxLength;

    private MessageType(String name, int id, int crcExtra, List<String> specs) {
        this.name = name;
        this.id = id;
        this.crcExtra = crcExtra;
        record Spec(String name, FieldType type, int arrayLength, boolean extension, int index) {
        }
        List<Spec> parsed = new ArrayList<>();
        boolean extension = false;
        for (String s : specs) {
            if (EXTENSIONS.equals(s)) {
                if (extension) {
                    throw new IllegalArgumentException("message " + name + ": " + EXTENSIONS + " appears twice");
                }
                extension = true;
                continue;
            }
            Matcher m = FIELD.matcher(s);
            if (!m.matches()) {
                throw new IllegalArgumentException("message " + name + ": field '" + s + "' is not 'type name' or 'type[N] name'");
            }
            int length = m.group(2) == null ? 0 : Integer.parseInt(m.group(2));
            if (m.group(2) != null && (length < 1 || length > 255)) {
                throw new IllegalArgumentException("message " + name + ": field '" + s + "' has an array length outside 1..255");
            }
            parsed.add(new Spec(m.group(3), FieldType.named(m.group(1)), length, extension, parsed.size()));
        }
        List<Spec> ordered = new ArrayList<>(parsed.stream().filter(f -> !f.extension()).toList());
        ordered.sort(Comparator.comparingInt((Spec f) -> f.type().size()).reversed()); // List.sort is stable
        parsed.stream().filter(Spec::extension).forEach(ordered::add);
        Field[] byIndex = new Field[parsed.size()];
        List<Field> wire = new ArrayList<>();
        int offset = 0;
        int base = 0;
        for (Spec s : ordered) {
            Field f = new Field(this, s.name(), s.type(), s.arrayLength(), s.extension(), offset);
            byIndex[s.index()] = f;
            wire.add(f);
            offset += f.size();
            if (!s.extension()) {
                base = offset;
            }
        }
        if (offset > Framing.MAX_PAYLOAD) {
            throw new IllegalArgumentException("message " + name + " has " + offset + " payload bytes; MAVLink allows " + Framing.MAX_PAYLOAD);
        }
        this.declared = List.of(byIndex);
        this.wireOrder = Collections.unmodifiableList(wire);
        Map<String, Field> names = new LinkedHashMap<>();
        for (Field f : declared) {
            if (names.put(f.name(), f) != null) {
                throw new IllegalArgumentException("message " + name + " has two fields named '" + f.name() + "'");
            }
        }
        this.byName = Collections.unmodifiableMap(names);
        this.baseLength = base;
        this.maxLength = offset;
    }

    /**
     * Defines a message from its definition.
     *
     * @param name     its name, {@code HEARTBEAT}
     * @param id       its id, 0 to {@value #MAX_ID}
     * @param crcExtra its CRC_EXTRA byte as the definition's generators give it
     * @param fields   its fields in declared order, {@code "uint32_t custom_mode"} or
     *                 {@code "char[50] text"}, with {@link #EXTENSIONS} before the extension fields
     * @return the message type
     * @throws IllegalArgumentException naming the message and the field that is wrong
     */
    public static MessageType define(String name, int id, int crcExtra, String... fields) {
        if (id < 0 || id > MAX_ID) {
            throw new IllegalArgumentException("message " + name + ": id " + id + " is outside 0.." + MAX_ID);
        }
        if (crcExtra < 0 || crcExtra > 0xFF) {
            throw new IllegalArgumentException("message " + name + ": CRC_EXTRA " + crcExtra + " is not a byte");
        }
        return new MessageType(name, id, crcExtra, List.of(fields));
    }

    /** @return its name */
    public String name() {
        return name;
    }

    /** @return its id */
    public int id() {
        return id;
    }

    /** @return its CRC_EXTRA byte */
    public int crcExtra() {
        return crcExtra;
    }

    /** @return its fields in declared order */
    public List<Field> fields() {
        return declared;
    }

    /** @return its fields in the order they are on the wire */
    public List<Field> wireOrder() {
        return wireOrder;
    }

    /** @return payload bytes of the fields before the extensions (a MAVLink 1 frame's length) */
    public int baseLength() {
        return baseLength;
    }

    /** @return payload bytes with every extension field */
    public int maxLength() {
        return maxLength;
    }

    /**
     * @param fieldName a field's name
     * @return the field
     * @throws IllegalArgumentException naming the message if it has no such field
     */
    public Field field(String fieldName) {
        Field f = byName.get(fieldName);
        if (f == null) {
            throw new IllegalArgumentException("message " + name + " has no field '" + fieldName + "'; it has " + byName.keySet());
        }
        return f;
    }

    /**
     * The CRC_EXTRA byte the message's definition gives, computed as mavgen does: the X.25 checksum
     * of {@code "NAME "}, then of each non-extension field in wire order as {@code "type name "}
     * (and its array length as one byte), folded to a byte (low XOR high).
     *
     * @return the computed CRC_EXTRA; equal to {@link #crcExtra()} when the fields are right
     */
    public int computedCrcExtra() {
        int crc = Crc.accumulate(Crc.INITIAL, (name + " ").getBytes(StandardCharsets.US_ASCII));
        for (Field f : wireOrder) {
            if (f.extension()) {
                break;
            }
            crc = Crc.accumulate(crc, (f.type().typeName() + " ").getBytes(StandardCharsets.US_ASCII));
            crc = Crc.accumulate(crc, (f.name() + " ").getBytes(StandardCharsets.US_ASCII));
            if (f.arrayLength() > 0) {
                crc = Crc.accumulate(crc, f.arrayLength());
            }
        }
        return (crc & 0xFF) ^ (crc >>> 8);
    }

    @Override
    public String toString() {
        return name + " (" + id + ")";
    }
}
