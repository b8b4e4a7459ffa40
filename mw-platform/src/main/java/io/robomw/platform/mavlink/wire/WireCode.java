package io.robomw.platform.mavlink.wire;

import java.util.Arrays;
import java.util.Map;
import java.util.Optional;
import java.util.function.Function;
import java.util.stream.Collectors;

/**
 * A value of a MAVLink enum, with its number on the wire ({@link #code()}; never the Java
 * ordinal). Each enum builds its lookup once with {@link #table}.
 */
public interface WireCode {

    /** @return its number on the wire */
    int code();

    /**
     * Looks codes up in one enum.
     *
     * @param <E> the enum
     */
    final class Table<E extends Enum<E> & WireCode> {
        private final String what;
        private final Map<Integer, E> byCode;

        private Table(Class<E> type, String what) {
            this.what = what;
            this.byCode = Arrays.stream(type.getEnumConstants()).collect(Collectors.toUnmodifiableMap(WireCode::code, Function.identity()));
        }

        /**
         * @param code a number from the wire
         * @return its value, if this enum has one (a peer may send a newer value)
         */
        public Optional<E> find(long code) {
            return code < Integer.MIN_VALUE || code > Integer.MAX_VALUE ? Optional.empty() : Optional.ofNullable(byCode.get((int) code));
        }

        /**
         * @param code a number from the wire
         * @return its value
         * @throws IllegalArgumentException naming the enum and the code when it has none
         */
        public E of(long code) {
            return find(code).orElseThrow(() -> new IllegalArgumentException(
                    "unknown " + what + " " + code + "; known: " + byCode.keySet()));
        }
    }

    /**
     * @param type the enum
     * @param what its MAVLink name, for errors ({@code MAV_TYPE})
     * @param <E>  the enum
     * @return its lookup
     */
    static <E extends Enum<E> & WireCode> Table<E> table(Class<E> type, String what) {
        return new Table<>(type, what);
    }
}
