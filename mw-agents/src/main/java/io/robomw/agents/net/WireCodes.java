package io.robomw.agents.net;

import java.util.Arrays;
import java.util.EnumSet;
import java.util.Optional;
import java.util.stream.Collectors;

/**
 * The table from codes back to the constants of one {@link WireCode} enum, built from its
 * {@code values()}: each code is written once, in its constant's constructor, and an unknown code
 * is an error that names the code, what it was meant to be and the codes known.
 *
 * <p>Building the table checks the codes: between 0 and {@value #MAX_CODE}, none used twice (a
 * mistake there fails the enum's class initialisation, so every test that touches it).
 *
 * @param <E> the enum
 */
public final class WireCodes<E extends Enum<E> & WireCode> {

    /** The largest code a table takes: codes travel in one or two bytes. */
    public static final int MAX_CODE = 0xFFFF;

    private final String what;
    private final E[] byCode;
    private final String known;

    private WireCodes(Class<E> type, String what) {
        this.what = what;
        E[] values = type.getEnumConstants();
        int max = Arrays.stream(values).mapToInt(WireCode::code).max().orElse(-1);
        @SuppressWarnings("unchecked")
        E[] table = (E[]) java.lang.reflect.Array.newInstance(type, max + 1);
        for (E e : values) {
            int c = e.code();
            if (c < 0 || c > MAX_CODE) {
                throw new IllegalStateException(what + " " + e + " has code " + c + ": codes are 0-" + MAX_CODE);
            }
            if (table[c] != null) {
                throw new IllegalStateException(what + " code " + c + " is given twice, to " + table[c] + " and " + e);
            }
            table[c] = e;
        }
        this.byCode = table;
        this.known = EnumSet.allOf(type).stream().map(e -> e.code() + " " + e).collect(Collectors.joining(", "));
    }

    /**
     * @param type the enum
     * @param what what its codes are, for error messages ("operation", "reply status")
     * @param <E>  the enum
     * @return its table
     */
    public static <E extends Enum<E> & WireCode> WireCodes<E> of(Class<E> type, String what) {
        return new WireCodes<>(type, what);
    }

    /**
     * @param code a code as read (unsigned)
     * @return its constant, or empty if none has it
     */
    public Optional<E> find(int code) {
        return code >= 0 && code < byCode.length ? Optional.ofNullable(byCode[code]) : Optional.empty();
    }

    /**
     * @param code a code as read (unsigned)
     * @return its constant
     * @throws IllegalArgumentException naming the code and the codes known if none has it
     */
    public E get(int code) {
        return find(code).orElseThrow(() -> new IllegalArgumentException(unknown(code)));
    }

    /** @return the message for an unknown code: "unknown WHAT code N (known: 0 A, 1 B, ...)" */
    public String unknown(int code) {
        return "unknown " + what + " code " + code + " (known: " + known + ")";
    }

    /** @return the codes known, "0 A, 1 B, ..." */
    public String known() {
        return known;
    }
}
