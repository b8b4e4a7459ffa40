package io.robomw.console.foxglove;

import com.fasterxml.jackson.core.JsonProcessingException;
import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.node.ObjectNode;

/** Jackson, shared by the package (an {@link ObjectMapper} is thread-safe once configured). */
final class Json {

    static final ObjectMapper MAPPER = new ObjectMapper();
    /** How much of a client's bad input an error quotes. */
    private static final int QUOTE = 80;

    private Json() {
    }

    static String write(ObjectNode n) {
        try {
            return MAPPER.writeValueAsString(n);
        } catch (JsonProcessingException e) {
            throw new IllegalStateException("cannot write a Foxglove message as JSON: " + e.getMessage(), e);
        }
    }

    /** @return the text, cut to a length fit for an error message */
    static String shortly(String text) {
        return text.length() <= QUOTE ? text : text.substring(0, QUOTE) + "... (" + text.length() + " characters)";
    }
}
