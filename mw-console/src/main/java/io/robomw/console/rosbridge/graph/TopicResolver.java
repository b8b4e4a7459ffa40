package io.robomw.console.rosbridge.graph;

import java.util.Optional;

/**
 * Makes topics the graph does not list yet exist when a client first names them: RoboMW
 * messaging topics ({@code /robomw/T}), which are bridged while someone uses them.
 */
@FunctionalInterface
public interface TopicResolver {

    /** Resolves nothing. */
    TopicResolver NONE = name -> Optional.empty();

    /**
     * @param name an absolute topic name the graph does not have
     * @return the topic, now in the graph, if this resolver makes such topics
     */
    Optional<Topic> resolve(String name);
}
