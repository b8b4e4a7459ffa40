package io.robomw.console.rosbridge.protocol;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.ObjectNode;

/**
 * One message from a client, with its fields read and checked as rosbridge_suite's
 * {@code basic_type_check} does: a required field that is missing, or a field of the wrong kind,
 * is an error naming the field, the kinds allowed and the value.
 *
 * @param op   the operation
 * @param id   its {@code id} as sent (any JSON value), echoed in replies; {@code null} if none
 * @param body the whole message
 */
record Request(Op op, JsonNode id, ObjectNode body) {

    /**
     * @param field a field's name
     * @return its text
     * @throws ProtocolException if it is missing or not text
     */
    String requiredText(String field) {
        JsonNode v = body.get(field);
        if (v == null) {
            throw new ProtocolException(op.wire() + " needs a '" + field + "' field");
        }
        return text(field, v);
    }

    /**
     * @param field a field's name
     * @return its text, or {@code null} if it is missing or null
     */
    String text(String field) {
        JsonNode v = body.get(field);
        return v == null || v.isNull() ? null : text(field, v);
    }

    private String text(String field, JsonNode v) {
        if (!v.isTextual()) {
            throw new ProtocolException("Expected field " + field + " to be one of [str]. Invalid value: " + v);
        }
        return v.asText();
    }

    /**
     * @param field    a field's name
     * @param fallback its value when missing or null
     * @param min      the smallest value allowed
     * @return its value
     * @throws ProtocolException if it is not a whole number at least {@code min}
     */
    int integer(String field, int fallback, int min) {
        JsonNode v = body.get(field);
        if (v == null || v.isNull()) {
            return fallback;
        }
        if (!v.isIntegralNumber() || !v.canConvertToInt() || v.intValue() < min) {
            throw new ProtocolException("Expected field " + field + " to be one of [int] (at least " + min + "). Invalid value: " + v);
        }
        return v.intValue();
    }

    /**
     * @param field a field's name
     * @return whether it is true (missing is false)
     * @throws ProtocolException if it is not a boolean
     */
    boolean flag(String field) {
        JsonNode v = body.get(field);
        if (v == null || v.isNull()) {
            return false;
        }
        if (!v.isBoolean()) {
            throw new ProtocolException("Expected field " + field + " to be one of [bool]. Invalid value: " + v);
        }
        return v.booleanValue();
    }

    /** @return its id as a string, for keys and log lines; {@code null} if it has none */
    String idText() {
        return id == null || id.isNull() ? null : id.isTextual() ? id.asText() : id.toString();
    }
}
