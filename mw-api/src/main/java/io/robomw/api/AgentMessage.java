package io.robomw.api;

import java.io.Serializable;

/**
 * A message sent to an agent through its {@link AgentRef} (after Aglets' {@code Message}), as the
 * agent's {@link Agent#handleMessage} sees it.
 */
public interface AgentMessage {

    /** @return what the sender sent */
    Serializable content();

    /**
     * Answers the message; the sender's {@link AgentRef#sendMessage} returns this value. Without
     * a reply the sender gets {@code null}. Only the first reply counts.
     *
     * @param reply the answer
     */
    void sendReply(Serializable reply);
}
