package io.robomw.console.rosbridge.graph;

import io.robomw.console.rosbridge.msg.ServiceType;

import java.util.Objects;

/**
 * A service of the bridge's graph.
 *
 * @param name    its absolute name, {@code /nxt/move}
 * @param type    its request and response types
 * @param node    the node that offers it, as rosapi lists it
 * @param handler what answers its calls
 */
public record Service(String name, ServiceType type, String node, ServiceHandler handler) {

    /** Checks that every part is given. */
    public Service {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(type, "type");
        Objects.requireNonNull(node, "node");
        Objects.requireNonNull(handler, "handler");
    }
}
