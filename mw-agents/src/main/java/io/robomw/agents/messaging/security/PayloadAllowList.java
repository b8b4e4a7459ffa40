package io.robomw.agents.messaging.security;

import java.io.ObjectInputFilter;
import java.util.Collection;
import java.util.HashSet;
import java.util.List;
import java.util.Set;

/**
 * The classes a messaging node deserializes in payloads; every other class is rejected before
 * it is loaded. Plain values (text, numbers, byte arrays) never go through Java serialization at
 * all (see {@link PayloadCodec}); this list is for objects.
 *
 * <p>The defaults are JDK value types that run no code of their own when read: boxed numbers,
 * {@code String}, {@code UUID}, {@code java.time} values, and the common lists, sets and maps.
 * Application types are added explicitly with {@link #with}; a record's component types must be
 * on the list too. Immutable.
 */
public final class PayloadAllowList {

    private static final List<String> JDK_DEFAULTS = List.of(
            "java.lang.String", "java.lang.Boolean", "java.lang.Byte", "java.lang.Character", "java.lang.Short",
            "java.lang.Integer", "java.lang.Long", "java.lang.Float", "java.lang.Double", "java.lang.Number", "java.lang.Enum",
            "java.math.BigInteger", "java.math.BigDecimal", "java.util.UUID", "java.time.Ser",
            "java.time.Instant", "java.time.Duration", "java.time.LocalDate", "java.time.LocalTime", "java.time.LocalDateTime",
            "java.util.ImmutableCollections$ListN", "java.util.ImmutableCollections$List12", "java.util.ImmutableCollections$SetN",
            "java.util.ImmutableCollections$Set12", "java.util.ImmutableCollections$MapN", "java.util.ImmutableCollections$Map1",
            "java.util.ArrayList", "java.util.LinkedList", "java.util.HashMap", "java.util.LinkedHashMap", "java.util.TreeMap",
            "java.util.HashSet", "java.util.LinkedHashSet", "java.util.TreeSet", "java.util.CollSer",
            "java.util.Collections$EmptyList", "java.util.Collections$EmptyMap", "java.util.Collections$EmptySet",
            "java.util.Collections$UnmodifiableList", "java.util.Collections$UnmodifiableRandomAccessList",
            "java.util.Collections$UnmodifiableCollection", "java.util.Collections$UnmodifiableMap",
            "java.util.Collections$UnmodifiableSet", "java.util.Arrays$ArrayList",
            // HashMap and HashSet check the Map.Entry[] they are about to make against the filter.
            "java.util.Map$Entry");

    /** Deepest object graph accepted. */
    public static final int MAX_DEPTH = 32;
    /** Most object references in one payload. */
    public static final int MAX_REFERENCES = 100_000;

    private final Set<String> classNames;

    private PayloadAllowList(Set<String> classNames) {
        this.classNames = Set.copyOf(classNames);
    }

    /** @return the JDK value types only */
    public static PayloadAllowList jdkDefaults() {
        return new PayloadAllowList(new HashSet<>(JDK_DEFAULTS));
    }

    /**
     * @param types application types to allow as well (records, enums, serializable classes)
     * @return this list plus those types
     */
    public PayloadAllowList with(Class<?>... types) {
        Set<String> names = new HashSet<>(classNames);
        for (Class<?> t : types) {
            names.add(t.getName());
        }
        return new PayloadAllowList(names);
    }

    /**
     * @param names fully qualified class names to allow as well (for JDK-internal classes that cannot be named as class literals)
     * @return this list plus those names
     */
    public PayloadAllowList withNames(Collection<String> names) {
        Set<String> all = new HashSet<>(classNames);
        all.addAll(names);
        return new PayloadAllowList(all);
    }

    /**
     * @param type a class
     * @return whether payloads may contain it
     */
    public boolean allows(Class<?> type) {
        Class<?> c = type;
        while (c.isArray()) {
            c = c.getComponentType();
            if (c == Object.class) {
                return true; // Object[] inside collections: each element is checked on its own
            }
        }
        return c.isPrimitive() || classNames.contains(c.getName());
    }

    /** @return the allowed class names */
    public Set<String> classNames() {
        return classNames;
    }

    /**
     * @param maxBytes the largest payload, which also bounds array lengths
     * @param why      told what was rejected: a class name, or the limit broken
     * @return a filter that allows these classes within the limits and rejects everything else
     */
    public ObjectInputFilter filter(long maxBytes, java.util.function.Consumer<String> why) {
        return info -> {
            if (info.depth() > MAX_DEPTH || info.references() > MAX_REFERENCES || info.streamBytes() > maxBytes
                    || info.arrayLength() > maxBytes) {
                why.accept("a limit was broken (depth " + info.depth() + " of " + MAX_DEPTH + ", references " + info.references()
                        + " of " + MAX_REFERENCES + ", bytes " + info.streamBytes() + " of " + maxBytes + ", array length " + info.arrayLength() + ")");
                return ObjectInputFilter.Status.REJECTED;
            }
            Class<?> c = info.serialClass();
            if (c == null) {
                return ObjectInputFilter.Status.ALLOWED;
            }
            if (allows(c)) {
                return ObjectInputFilter.Status.ALLOWED;
            }
            why.accept("class " + c.getName() + " is not on the allow-list");
            return ObjectInputFilter.Status.REJECTED;
        };
    }
}
