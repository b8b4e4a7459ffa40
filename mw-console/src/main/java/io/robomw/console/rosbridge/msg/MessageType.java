package io.robomw.console.rosbridge.msg;

import java.util.List;
import java.util.Optional;

/**
 * A message type: its fields in order, its constants, and the text of its definition.
 *
 * @param name       its name ({@code pkg/msg/Type}; a service's request and response are
 *                   {@code pkg/srv/Type_Request} and {@code _Response})
 * @param fields     the fields, in order
 * @param constants  the constants
 * @param definition the definition as its interface file writes it
 */
public record MessageType(TypeName name, List<Field> fields, List<Constant> constants, String definition) {

    /** Copies the lists. */
    public MessageType {
        fields = List.copyOf(fields);
        constants = List.copyOf(constants);
    }

    /**
     * @param fieldName a field's name
     * @return that field, if the type has it
     */
    public Optional<Field> field(String fieldName) {
        for (Field f : fields) {
            if (f.name().equals(fieldName)) {
                return Optional.of(f);
            }
        }
        return Optional.empty();
    }
}
