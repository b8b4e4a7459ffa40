package io.robomw.api.spi;

import java.util.HashMap;
import java.util.Map;
import java.util.Optional;

/**
 * Services a program hands to the platforms it opens, looked up by type: for example the
 * simulated world that {@code platform: sim} robots live in. Immutable; {@link #with} returns a
 * new instance.
 */
public final class PlatformServices {

    private static final PlatformServices NONE = new PlatformServices(Map.of());

    private final Map<Class<?>, Object> services;

    private PlatformServices(Map<Class<?>, Object> services) {
        this.services = Map.copyOf(services);
    }

    /** @return no services */
    public static PlatformServices none() {
        return NONE;
    }

    /**
     * @param type    the service's type, the key it is found by
     * @param service the service
     * @param <T>     the type
     * @return these services plus that one (replacing one of the same type)
     */
    public <T> PlatformServices with(Class<T> type, T service) {
        Map<Class<?>, Object> copy = new HashMap<>(services);
        copy.put(type, type.cast(service));
        return new PlatformServices(copy);
    }

    /**
     * @param type the service's type
     * @param <T>  the type
     * @return the service, if given
     */
    public <T> Optional<T> find(Class<T> type) {
        return Optional.ofNullable(services.get(type)).map(type::cast);
    }
}
