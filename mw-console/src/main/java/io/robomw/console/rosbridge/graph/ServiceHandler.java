package io.robomw.console.rosbridge.graph;

import com.fasterxml.jackson.databind.node.ObjectNode;

import java.util.concurrent.CompletableFuture;

/**
 * Answers a service's calls. Called on a client's connection thread: a handler returns at once
 * and completes the future later (a robot's move completes when the robot has moved).
 */
@FunctionalInterface
public interface ServiceHandler {

    /**
     * @param request the call's arguments, read against the service's request type (every field present)
     * @return completes with the response's fields (missing ones get their defaults), or
     *         exceptionally: the client gets {@code result: false} with the failure's message
     */
    CompletableFuture<ObjectNode> call(ObjectNode request);
}
