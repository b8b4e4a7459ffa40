package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.Address;

/**
 * The {@code shm} option of a {@code tcp://} address: {@code tcp://127.0.0.1:7000?shm=off} keeps
 * every frame of the connections made or accepted there on TCP, whatever the node's settings say;
 * {@code shm=on} (or no option) leaves it to them.
 */
final class SharedMemoryOption {

    /** The query key. */
    static final String KEY = "shm";

    private SharedMemoryOption() {
    }

    /**
     * @param address a tcp address
     * @return whether it lets its connections use shared memory
     * @throws IllegalArgumentException naming the address and the values allowed, for any other value
     */
    static boolean allows(Address address) {
        String v = address.query().get(KEY);
        if (v == null || v.equals("on")) {
            return true;
        }
        if (v.equals("off")) {
            return false;
        }
        throw new IllegalArgumentException("'" + address + "?" + KEY + "=" + v + "': " + KEY + " is 'on' or 'off'");
    }
}
