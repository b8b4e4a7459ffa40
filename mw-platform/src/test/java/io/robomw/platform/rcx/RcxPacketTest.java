package io.robomw.platform.rcx;

import org.junit.jupiter.api.Test;

import java.util.HexFormat;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** RCX packets against the byte examples of protocols §3.3 and §3.5 (checked there with NQC). */
class RcxPacketTest {

    private static byte[] hex(String s) {
        return HexFormat.of().parseHex(s.replace(" ", ""));
    }

    @Test
    void shouldEncodeTheDocumentedMotorPackets() {
        assertArrayEquals(hex("55 FF 00 E1 1E 81 7E 62 9D"), RcxPacket.encode(RcxPacket.SET_MOTOR_DIRECTION,
                RcxPacket.setMotorDirection(RcxPacket.MOTOR_A, RcxPacket.FORWARD)), "motor A forward");
        assertArrayEquals(hex("55 FF 00 13 EC 01 FE 02 FD 07 F8 1D E2"), RcxPacket.encode(RcxPacket.SET_MOTOR_POWER,
                RcxPacket.setMotorPower(RcxPacket.MOTOR_A, 7)), "power A = constant 7");
        assertArrayEquals(hex("55 FF 00 21 DE 81 7E A2 5D"), RcxPacket.encode(RcxPacket.SET_MOTOR_ON_OFF,
                RcxPacket.setMotorOnOff(RcxPacket.MOTOR_A, RcxPacket.ON)), "motor A on");
        assertArrayEquals(hex("55 FF 00 29 D6 81 7E AA 55"), RcxPacket.encode(RcxPacket.SET_MOTOR_ON_OFF | RcxPacket.TOGGLE,
                RcxPacket.setMotorOnOff(RcxPacket.MOTOR_A, RcxPacket.ON)), "the same again, toggle bit set");
        assertArrayEquals(hex("55 FF 00 21 DE 45 BA 66 99"), RcxPacket.encode(RcxPacket.SET_MOTOR_ON_OFF,
                RcxPacket.setMotorOnOff(RcxPacket.MOTOR_A | RcxPacket.MOTOR_C, RcxPacket.OFF)), "A and C off (brake)");
        assertArrayEquals(hex("55 FF 00 21 DE 02 FD 23 DC"), RcxPacket.encode(RcxPacket.SET_MOTOR_ON_OFF,
                RcxPacket.setMotorOnOff(RcxPacket.MOTOR_B, RcxPacket.FLOAT)), "B float");
    }

    @Test
    void shouldEncodeTheDocumentedSensorAndBatteryPackets() {
        assertArrayEquals(hex("55 FF 00 12 ED 0C F3 00 FF 1E E1"), RcxPacket.encode(RcxPacket.GET_VALUE,
                RcxPacket.getValue(RcxPacket.SOURCE_SENSOR_RAW, 0)), "raw value of S1");
        assertArrayEquals(hex("55 FF 00 12 ED 0D F2 00 FF 1F E0"), RcxPacket.encode(RcxPacket.GET_VALUE,
                RcxPacket.getValue(RcxPacket.SOURCE_SENSOR_BOOLEAN, 0)), "boolean value of S1");
        assertArrayEquals(hex("55 FF 00 30 CF 30 CF"), RcxPacket.encode(RcxPacket.GET_BATTERY), "battery");
        assertArrayEquals(hex("55 FF 00 32 CD 00 FF 01 FE 33 CC"), RcxPacket.encode(RcxPacket.SET_SENSOR_TYPE,
                RcxPacket.setSensorType(0, RcxPacket.TYPE_TOUCH)), "S1 touch");
        assertArrayEquals(hex("55 FF 00 42 BD 00 FF 20 DF 62 9D"), RcxPacket.encode(RcxPacket.SET_SENSOR_MODE,
                RcxPacket.setSensorMode(0, RcxPacket.MODE_BOOLEAN)), "S1 boolean");
        assertArrayEquals(hex("55 FF 00 10 EF 10 EF"), RcxPacket.encode(RcxPacket.ALIVE), "alive, as nqc pings");
        assertArrayEquals(hex("55 FF 00 18 E7 18 E7"), RcxPacket.encode(RcxPacket.ALIVE | RcxPacket.TOGGLE), "alive with the toggle bit");
    }

    @Test
    void shouldDecodeTheDocumentedReplies() {
        RcxPacket.Decoded raw = RcxPacket.decode(hex("55 FF 00 ED 12 F3 0C 02 FD E2 1D"));
        assertEquals(RcxPacket.replyOpcode(RcxPacket.GET_VALUE), raw.opcode());
        assertEquals(755, raw.s16());
        assertEquals(1, RcxPacket.decode(hex("55 FF 00 ED 12 01 FE 00 FF EE 11")).s16());
        assertEquals(9300, RcxPacket.decode(hex("55 FF 00 CF 30 54 AB 24 DB 47 B8")).u16(), "battery, mV");
        assertEquals(0x1E, RcxPacket.decode(hex("55 FF 00 1E E1 1E E1")).opcode(), "reply to E1: its complement");
        assertEquals(0xE7, RcxPacket.decode(hex("55 ff 00 e7 18 e7 18")).opcode(), "reply to a toggled alive: toggle bit included");
    }

    @Test
    void shouldRefuseAByteNotFollowedByItsComplement() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> RcxPacket.decode(hex("55 FF 00 ED 12 F3 0D 02 FD E2 1D")));
        assertTrue(e.getMessage().contains("complement"), e.getMessage());
    }

    @Test
    void shouldRefuseAWrongChecksum() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> RcxPacket.decode(hex("55 FF 00 ED 12 F3 0C 02 FD E3 1C")));
        assertTrue(e.getMessage().contains("checksum"), e.getMessage());
    }

    @Test
    void shouldRefuseAWrongHeaderOrLength() {
        assertThrows(IllegalArgumentException.class, () -> RcxPacket.decode(hex("55 FE 00 10 EF 10 EF")));
        assertThrows(IllegalArgumentException.class, () -> RcxPacket.decode(hex("55 FF 00 10 EF 10")));
    }

    @Test
    void shouldKnowEveryOpcodesLengthsWithOrWithoutTheToggleBit() {
        assertEquals(2, RcxPacket.requestDataLength(RcxPacket.GET_VALUE | RcxPacket.TOGGLE));
        assertEquals(2, RcxPacket.replyDataLength(RcxPacket.GET_VALUE));
        assertEquals(3, RcxPacket.requestDataLength(RcxPacket.SET_MOTOR_POWER));
        assertEquals(0, RcxPacket.replyDataLength(RcxPacket.SET_MOTOR_DIRECTION | RcxPacket.TOGGLE));
        assertEquals(8, RcxPacket.replyDataLength(RcxPacket.GET_VERSIONS));
        assertEquals(-1, RcxPacket.requestDataLength(0x99), "not an opcode the codec knows");
    }

    @Test
    void shouldMapSpeedsToTheNearestPowerStep() {
        assertEquals(7, RcxMotorDriver.powerStep(600));
        assertEquals(0, RcxMotorDriver.powerStep(10));
        assertEquals(2, RcxMotorDriver.powerStep(-205), "0.10 m/s on 56 mm wheels: 205 °/s, step 2 turns at 225 °/s");
        assertEquals(225, RcxMotorDriver.speedAt(2), 1e-9);
    }
}
