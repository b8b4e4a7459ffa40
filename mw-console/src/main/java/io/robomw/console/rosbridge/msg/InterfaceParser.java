package io.robomw.console.rosbridge.msg;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;

import java.math.BigDecimal;
import java.util.ArrayList;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * Reads ROS 2 interface files ({@code .msg}, {@code .srv}) in the subset the bridge's own
 * definitions use: fields ({@code float64[36] covariance}), arrays of any shape
 * ({@code []}, {@code [N]}, {@code [<=N]}), numeric defaults ({@code float64 w 1}), constants
 * ({@code uint8 INFRARED=1}), {@code #} comments and the {@code ---} between a service's request
 * and response. A type without a package is in the file's own package, except {@code Header},
 * which is {@code std_msgs/Header}, as in ROS.
 */
final class InterfaceParser {

    private static final Pattern FIELD = Pattern.compile("([A-Za-z][A-Za-z0-9_/]*)(\\[(<=)?(\\d*)\\])?\\s+([a-z][a-z0-9_]*)(\\s+(\\S+))?");
    private static final Pattern CONSTANT = Pattern.compile("([a-z][a-z0-9]*)\\s+([A-Z][A-Z0-9_]*)\\s*=\\s*(\\S+)");
    private static final JsonNodeFactory NODES = JsonNodeFactory.instance;

    private InterfaceParser() {
    }

    /**
     * @param name the message's name
     * @param text its definition
     * @return the message type
     * @throws IllegalArgumentException naming the type and line if a line is not a field, a constant or a comment
     */
    static MessageType message(TypeName name, String text) {
        return parseMessage(name, text.lines().toList(), text);
    }

    /**
     * @param name the service's name
     * @param text its definition: request fields, {@code ---}, response fields
     * @return the service type
     */
    static ServiceType service(TypeName name, String text) {
        List<String> lines = text.lines().toList();
        int separator = -1;
        for (int i = 0; i < lines.size(); i++) {
            if (stripComment(lines.get(i)).equals("---")) {
                separator = i;
                break;
            }
        }
        if (separator < 0) {
            throw new IllegalArgumentException(name + ": a service definition needs '---' between its request and its response");
        }
        TypeName requestName = new TypeName(name.pkg(), TypeName.Kind.SRV, name.name() + "_Request");
        TypeName responseName = new TypeName(name.pkg(), TypeName.Kind.SRV, name.name() + "_Response");
        MessageType request = parseMessage(requestName, lines.subList(0, separator), String.join("\n", lines.subList(0, separator)));
        MessageType response = parseMessage(responseName, lines.subList(separator + 1, lines.size()),
                String.join("\n", lines.subList(separator + 1, lines.size())));
        return new ServiceType(name, request, response, text);
    }

    private static MessageType parseMessage(TypeName name, List<String> lines, String text) {
        List<Field> fields = new ArrayList<>();
        List<Constant> constants = new ArrayList<>();
        for (int i = 0; i < lines.size(); i++) {
            String line = stripComment(lines.get(i));
            if (line.isEmpty()) {
                continue;
            }
            Matcher c = CONSTANT.matcher(line);
            if (c.matches()) {
                Primitive p = Primitive.ofFileName(c.group(1));
                if (p == null) {
                    throw new IllegalArgumentException(name + " line " + (i + 1) + ": constant " + c.group(2) + " must have a built-in type, got " + c.group(1));
                }
                constants.add(new Constant(c.group(2), p, c.group(3)));
                continue;
            }
            Matcher f = FIELD.matcher(line);
            if (!f.matches()) {
                throw new IllegalArgumentException(name + " line " + (i + 1) + ": '" + line + "' is neither a field ('type name') nor a constant ('type NAME=value')");
            }
            fields.add(field(name, f));
        }
        return new MessageType(name, fields, constants, text.strip());
    }

    private static Field field(TypeName owner, Matcher f) {
        String type = f.group(1);
        Field.Shape shape = Field.Shape.SINGLE;
        int length = 0;
        if (f.group(2) != null) {
            boolean bounded = f.group(3) != null;
            String digits = f.group(4);
            if (digits.isEmpty()) {
                shape = Field.Shape.SEQUENCE;
            } else {
                shape = bounded ? Field.Shape.SEQUENCE : Field.Shape.FIXED;
                length = Integer.parseInt(digits);
            }
        }
        Primitive primitive = Primitive.ofFileName(type);
        TypeName message = primitive != null ? null : reference(owner, type);
        JsonNode defaultValue = null;
        if (f.group(7) != null) {
            if (primitive == null || !primitive.numeric() || shape != Field.Shape.SINGLE) {
                throw new IllegalArgumentException(owner + ": field " + f.group(5) + " has a default, which only single numbers may have here");
            }
            defaultValue = NODES.numberNode(new BigDecimal(f.group(7)));
        }
        return new Field(f.group(5), primitive, message, shape, length, defaultValue);
    }

    private static TypeName reference(TypeName owner, String type) {
        if (type.equals("Header")) {
            return new TypeName("std_msgs", TypeName.Kind.MSG, "Header");
        }
        int slash = type.indexOf('/');
        if (slash < 0) {
            return new TypeName(owner.pkg(), TypeName.Kind.MSG, type);
        }
        return TypeName.parse(type, TypeName.Kind.MSG);
    }

    private static String stripComment(String line) {
        int hash = line.indexOf('#');
        return (hash < 0 ? line : line.substring(0, hash)).strip();
    }
}
