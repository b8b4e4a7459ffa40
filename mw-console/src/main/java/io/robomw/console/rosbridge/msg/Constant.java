package io.robomw.console.rosbridge.msg;

/**
 * A constant of a message type: {@code uint8 ULTRASOUND=0}.
 *
 * @param name  its name
 * @param type  its built-in type
 * @param value its value as the interface file writes it
 */
public record Constant(String name, Primitive type, String value) {
}
