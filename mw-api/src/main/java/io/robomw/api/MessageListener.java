package io.robomw.api;

/**
 * Receives the messages of a topic it was registered for with
 * {@link Messaging#addMessageListener}. Called on a messaging thread; a listener that throws is
 * logged and keeps receiving.
 */
@FunctionalInterface
public interface MessageListener {

    /**
     * Called once for each message delivered.
     *
     * @param message the message
     */
    void onMessage(Message message);
}
