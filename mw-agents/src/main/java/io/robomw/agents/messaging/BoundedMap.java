package io.robomw.agents.messaging;

import java.util.LinkedHashMap;
import java.util.Map;

/**
 * A synchronized map that forgets its oldest entries beyond a size: the requests a node sent
 * (to verify and route their replies) and the requests it received (to send replies back).
 *
 * @param <K> key type
 * @param <V> value type
 */
final class BoundedMap<K, V> {

    private final Map<K, V> map;

    BoundedMap(int maxSize) {
        map = new LinkedHashMap<>(1024, 0.75f, false) {
            private static final long serialVersionUID = 1L;

            @Override
            protected boolean removeEldestEntry(Map.Entry<K, V> eldest) {
                return size() > maxSize;
            }
        };
    }

    synchronized void put(K key, V value) {
        map.put(key, value);
    }

    synchronized V get(K key) {
        return map.get(key);
    }
}
