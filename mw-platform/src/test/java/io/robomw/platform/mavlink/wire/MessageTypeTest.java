package io.robomw.platform.mavlink.wire;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

import java.util.HashSet;
import java.util.List;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class MessageTypeTest {

    static List<MessageType> dialect() {
        return Messages.ALL;
    }

    @ParameterizedTest
    @MethodSource("dialect")
    void crcExtraComputedFromTheFieldsIsTheDocumentedOne(MessageType type) {
        assertEquals(type.crcExtra(), type.computedCrcExtra(), type + ": its fields do not give its CRC_EXTRA");
    }

    @Test
    void everyMessageIdIsUniqueAndFoundById() {
        Set<Integer> ids = new HashSet<>();
        for (MessageType t : Messages.ALL) {
            assertTrue(ids.add(t.id()), "two messages have id " + t.id());
            assertEquals(t, Messages.byId(t.id()));
        }
    }

    @Test
    void documentedIdsAndCrcExtrasOfTheFactsTable() {
        int[][] table = {{0, 50, 9}, {1, 124, 43}, {2, 137, 12}, {4, 237, 14}, {11, 89, 6}, {20, 214, 20}, {21, 159, 2}, {22, 220, 25},
                {23, 168, 23}, {24, 24, 52}, {30, 39, 28}, {32, 185, 28}, {33, 104, 28}, {44, 221, 5}, {47, 153, 4}, {46, 11, 2},
                {76, 152, 33}, {75, 158, 35}, {77, 143, 10}, {82, 49, 39}, {84, 143, 53}, {85, 140, 51}, {111, 34, 16}, {132, 85, 39},
                {147, 154, 54}, {148, 178, 78}, {242, 104, 60}, {245, 130, 2}, {253, 83, 54}, {256, 71, 42}, {73, 38, 38},
                {51, 196, 5}, {74, 20, 20}, {42, 28, -1}};
        for (int[] row : table) {
            MessageType t = Messages.byId(row[0]);
            assertEquals(row[1], t.crcExtra(), t.name());
            if (row[2] >= 0) {
                assertEquals(row[2], t.maxLength(), t.name() + " length");
            }
        }
    }

    @Test
    void heartbeatIsSentCustomModeFirst() {
        assertEquals(List.of("custom_mode", "type", "autopilot", "base_mode", "system_status", "mavlink_version"),
                Messages.Heartbeat.MESSAGE.wireOrder().stream().map(Field::name).toList());
    }

    @Test
    void setPositionTargetIsSentFloatsThenTypeMaskThenBytes() {
        assertEquals(List.of("time_boot_ms", "x", "y", "z", "vx", "vy", "vz", "afx", "afy", "afz", "yaw", "yaw_rate", "type_mask",
                        "target_system", "target_component", "coordinate_frame"),
                Messages.SetPositionTargetLocalNed.MESSAGE.wireOrder().stream().map(Field::name).toList());
    }

    @Test
    void commandLongIsSentParamsThenCommandThenTargets() {
        assertEquals(List.of("param1", "param2", "param3", "param4", "param5", "param6", "param7", "command", "target_system",
                        "target_component", "confirmation"),
                Messages.CommandLong.MESSAGE.wireOrder().stream().map(Field::name).toList());
    }

    @Test
    void extensionsComeLastInDeclaredOrderAndAreNotCountedInTheBaseLength() {
        MessageType t = Messages.SysStatus.MESSAGE;
        List<Field> wire = t.wireOrder();
        assertEquals("onboard_control_sensors_present_extended", wire.get(wire.size() - 3).name());
        assertEquals("onboard_control_sensors_health_extended", wire.get(wire.size() - 1).name());
        assertEquals(31, t.baseLength());
        assertEquals(43, t.maxLength());
        // a small extension (uint8) stays after the large fields it follows in the declaration
        assertEquals(List.of("severity", "text", "id", "chunk_seq"), Messages.Statustext.MESSAGE.wireOrder().stream().map(Field::name).toList());
    }

    @Test
    void aFieldOfAnotherMessageIsRefusedByName() {
        Payload p = Payload.of(Messages.Heartbeat.MESSAGE);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> p.getLong(Messages.CommandAck.COMMAND));
        assertTrue(e.getMessage().contains("COMMAND_ACK.command") && e.getMessage().contains("HEARTBEAT"), e.getMessage());
    }

    @Test
    void aMalformedDefinitionIsRefusedNamingTheField() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> MessageType.define("X", 1, 2, "uint9_t a"));
        assertTrue(e.getMessage().contains("uint9_t"), e.getMessage());
        e = assertThrows(IllegalArgumentException.class, () -> MessageType.define("X", 1 << 24, 2, "uint8_t a"));
        assertTrue(e.getMessage().contains("16777216"), e.getMessage());
    }
}
