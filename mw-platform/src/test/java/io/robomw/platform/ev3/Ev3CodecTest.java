package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.motor.MotorState;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import java.util.ArrayList;
import java.util.HexFormat;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The EV3 codec against the byte examples of the protocol notes (section 2.3, parameter encodings,
 * and section 2.5, complete commands and replies), in both directions: each example is built with
 * the encoders and compared byte for byte, and decoded back into header fields, opcodes and
 * parameters. Then the edge cases: partial frames, maximum globals, error replies.
 */
class Ev3CodecTest {

    static byte[] hex(String spaced) {
        return HexFormat.of().parseHex(spaced.replaceAll("[\\s:|]", ""));
    }

    static String hex(byte[] bytes) {
        return HexFormat.ofDelimiter(" ").withUpperCase().formatHex(bytes);
    }

    /** Decodes every parameter after the opcode of a one-instruction byte-code string. */
    private static List<Ev3Parameter> parameters(Ev3CodeReader reader) {
        List<Ev3Parameter> out = new ArrayList<>();
        while (reader.hasMore()) {
            out.add(reader.nextParameter());
        }
        return out;
    }

    private static List<Ev3Parameter> constants(int... values) {
        List<Ev3Parameter> out = new ArrayList<>();
        for (int v : values) {
            out.add(Ev3Parameter.constant(v));
        }
        return out;
    }

    // ---- 2.3 parameter encoding ----

    @ParameterizedTest(name = "{0} -> {1}")
    @CsvSource({
            "0, 00",
            "31, 1F",
            "32, 81 20",
            "-1, 3F",
            "-32, 20",
            "-33, 81 DF",
            "720, 82 D0 02",
            "-720, 82 30 FD",
            "40000, 83 40 9C 00 00"})
    void shouldEncodeConstantInShortestFormAsEv3DcLcx(int value, String expected) {
        assertEquals(expected, hex(Ev3Parameter.lc(value)));
    }

    @ParameterizedTest(name = "{1} -> {0}")
    @CsvSource({
            "0, 00",
            "31, 1F",
            "32, 81 20",
            "-1, 3F",
            "-32, 20",
            "-33, 81 DF",
            "720, 82 D0 02",
            "-720, 82 30 FD",
            "40000, 83 40 9C 00 00"})
    void shouldDecodeConstantOfEveryDocumentedForm(int expected, String encoded) {
        byte[] b = hex(encoded);
        Ev3CodeReader reader = new Ev3CodeReader(b, 0, b.length);
        assertEquals(Ev3Parameter.constant(expected), reader.nextParameter());
        assertFalse(reader.hasMore());
    }

    @Test
    void shouldDecodeLongFormsOfSmallConstants() {
        byte[] b = hex("81 05 82 05 00 83 05 00 00 00 83 FF FF FF FF");
        assertEquals(constants(5, 5, 5, -1), parameters(new Ev3CodeReader(b, 0, b.length)));
    }

    @Test
    void shouldEncodeExplicitConstantFormsAsTheMacros() {
        assertEquals("05", hex(Ev3Parameter.lc0(5)));
        assertEquals("81 05", hex(Ev3Parameter.lc1(5)));
        assertEquals("82 05 00", hex(Ev3Parameter.lc2(5)));
        assertEquals("83 05 00 00 00", hex(Ev3Parameter.lc4(5)));
    }

    @Test
    void shouldRejectConstantTooBigForTheAskedForm() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Ev3Parameter.lc0(32));
        assertTrue(e.getMessage().contains("LC0 holds -32..31, got 32"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> Ev3Parameter.lc1(128));
        assertThrows(IllegalArgumentException.class, () -> Ev3Parameter.lc2(32768));
    }

    @Test
    void shouldEncodeAndDecodeStringConstant() {
        assertEquals("84 78 00", hex(Ev3Parameter.lcs("x")));
        byte[] b = hex("84 78 00 80 61 62 00");
        assertEquals(List.of(Ev3Parameter.string("x"), Ev3Parameter.string("ab")), parameters(new Ev3CodeReader(b, 0, b.length)));
        assertThrows(IllegalArgumentException.class, () -> Ev3Parameter.lcs("a\0b"));
    }

    @ParameterizedTest(name = "GV({0}) -> {1}")
    @CsvSource({
            "0, 60",
            "31, 7F",
            "32, E1 20",
            "255, E1 FF",
            "256, E2 00 01",
            "65536, E3 00 00 01 00"})
    void shouldEncodeGlobalReferenceInShortestFormAndDecodeIt(int offset, String expected) {
        assertEquals(expected, hex(Ev3Parameter.gv(offset)));
        byte[] b = hex(expected);
        assertEquals(Ev3Parameter.global(offset), new Ev3CodeReader(b, 0, b.length).nextParameter());
    }

    @ParameterizedTest(name = "LV({0}) -> {1}")
    @CsvSource({
            "0, 40",
            "31, 5F",
            "32, C1 20",
            "256, C2 00 01"})
    void shouldEncodeLocalReferenceInShortestFormAndDecodeIt(int offset, String expected) {
        assertEquals(expected, hex(Ev3Parameter.lv(offset)));
        byte[] b = hex(expected);
        assertEquals(Ev3Parameter.local(offset), new Ev3CodeReader(b, 0, b.length).nextParameter());
    }

    @Test
    void shouldEncodeExplicitVariableFormsAsTheMacros() {
        assertEquals("60", hex(Ev3Parameter.gv0(0)));
        assertEquals("E1 04", hex(Ev3Parameter.gv1(4)));
        assertEquals("E2 04 00", hex(Ev3Parameter.gv2(4)));
        assertEquals("E3 04 00 00 00", hex(Ev3Parameter.gv4(4)));
        assertEquals("44", hex(Ev3Parameter.lv0(4)));
        assertThrows(IllegalArgumentException.class, () -> Ev3Parameter.gv0(32));
    }

    @Test
    void shouldRejectParameterCutOffByTheEndOfTheByteCodesNamingTheOffset() {
        byte[] b = hex("AE 00 02 82 D0");
        Ev3CodeReader reader = new Ev3CodeReader(b, 0, b.length);
        reader.nextByte();
        reader.nextParameter();
        reader.nextParameter();
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, reader::nextParameter);
        assertTrue(e.getMessage().contains("byte 3"), e.getMessage());
    }

    @Test
    void shouldRejectStringWithoutTerminatingNul() {
        byte[] b = hex("84 78 79");
        assertThrows(IllegalArgumentException.class, () -> new Ev3CodeReader(b, 0, b.length).nextParameter());
    }

    @Test
    void shouldRejectLabelsAndHandlesWhichDirectCommandsDoNotUse() {
        byte[] label = hex("A1 00");
        assertThrows(IllegalArgumentException.class, () -> new Ev3CodeReader(label, 0, label.length).nextParameter());
        byte[] handle = hex("D1 00");
        assertThrows(IllegalArgumentException.class, () -> new Ev3CodeReader(handle, 0, handle.length).nextParameter());
    }

    @Test
    void shouldDecodeDataTypesLittleEndianIncludingFloatOne() {
        Ev3Reply r = Ev3Reply.decode(hex("0E 00 01 00 02 | FE | 34 12 | 68 01 00 00 | 00 00 80 3F"));
        assertEquals(-2, r.data8(0));
        assertEquals(0x1234, r.data16(1));
        assertEquals(360, r.data32(3));
        assertEquals(1.0f, r.dataF(7));
        assertThrows(IndexOutOfBoundsException.class, () -> r.dataF(9));
    }

    @Test
    void shouldDecodeNanMarkers() {
        Ev3Reply r = Ev3Reply.decode(hex("0E 00 01 00 02 | 80 | 00 80 | 00 00 00 80 | 00 00 C0 7F"));
        assertEquals(Ev3Reply.NAN_DATA8, r.data8(0));
        assertEquals(Ev3Reply.NAN_DATA16, r.data16(1));
        assertEquals(Ev3Reply.NAN_DATA32, r.data32(3));
        assertTrue(Float.isNaN(r.dataF(7)));
    }

    // ---- 2.5 complete examples ----

    @Test
    void shouldEncodeStepSpeedExampleRunMotorB720DegreesThenBrake() {
        Ev3Command c = Ev3Command.withoutReply().outputStepSpeed(0x02, 50, 0, 720, 0, MotorState.StopMode.BRAKE).build();
        assertEquals("10 00 2A 00 80 00 00 AE 00 02 81 32 00 82 D0 02 00 01", hex(c.encode(42)));
    }

    @Test
    void shouldDecodeStepSpeedExample() {
        byte[] frame = hex("10 00 | 2A 00 | 80 | 00 00 | AE 00 02 81 32 00 82 D0 02 00 01");
        assertEquals(16, Ev3Frame.length(frame));
        assertEquals(42, Ev3Frame.counter(frame));
        assertEquals(Ev3Frame.DIRECT_COMMAND_NO_REPLY, Ev3Frame.type(frame));
        int vars = LittleEndian.u16(frame, Ev3Frame.VARS_FIELD_OFFSET);
        assertEquals(0, Ev3Frame.globalsOf(vars));
        assertEquals(0, Ev3Frame.localsOf(vars));
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(frame);
        assertEquals(Ev3Opcode.OUTPUT_STEP_SPEED.code(), reader.nextByte());
        assertEquals(constants(0, 2, 50, 0, 720, 0, 1), parameters(reader));
    }

    @Test
    void shouldEncodeGetCountExampleWithFourGlobals() {
        Ev3Command c = Ev3Command.withReply(4).outputGetCount(0, 0).build();
        assertEquals("09 00 2B 00 00 04 00 B3 00 00 60", hex(c.encode(0x2B)));
    }

    @Test
    void shouldDecodeGetCountExampleRequest() {
        byte[] frame = hex("09 00 2B 00 00 04 00 B3 00 00 60");
        assertEquals(0x2B, Ev3Frame.counter(frame));
        assertEquals(Ev3Frame.DIRECT_COMMAND_REPLY, Ev3Frame.type(frame));
        assertEquals(4, Ev3Frame.globalsOf(LittleEndian.u16(frame, Ev3Frame.VARS_FIELD_OFFSET)));
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(frame);
        assertEquals(Ev3Opcode.OUTPUT_GET_COUNT.code(), reader.nextByte());
        assertEquals(List.of(Ev3Parameter.constant(0), Ev3Parameter.constant(0), Ev3Parameter.global(0)), parameters(reader));
    }

    @Test
    void shouldEncodeAndDecodeGetCountExampleReply360() {
        byte[] documented = hex("07 00 2B 00 02 68 01 00 00");
        Ev3Reply reply = Ev3Reply.decode(documented);
        assertEquals(0x2B, reply.counter());
        assertTrue(reply.isOk());
        assertEquals(360, reply.data32(0));
        byte[] globals = new byte[4];
        LittleEndian.putU32(globals, 0, 360);
        assertArrayEquals(documented, Ev3Reply.ok(0x2B, globals).encode());
    }

    @Test
    void shouldEncodeTouchReadySiExampleFromEv3DcTrace() {
        Ev3Command c = Ev3Command.withReply(4).inputReadySi(0, Ev3Device.TOUCH.type(), 0, 0).build();
        assertEquals("0D 00 2A 00 00 04 00 99 1D 00 00 10 00 01 60", hex(c.encode(0x2A)));
    }

    @Test
    void shouldDecodeTouchReadySiExampleRequest() {
        byte[] frame = hex("0D 00 2A 00 00 04 00 99 1D 00 00 10 00 01 60");
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(frame);
        assertEquals(Ev3Opcode.INPUT_DEVICE.code(), reader.nextByte());
        assertEquals(List.of(Ev3Parameter.constant(Ev3Subcode.READY_SI.code()), Ev3Parameter.constant(0), Ev3Parameter.constant(0),
                Ev3Parameter.constant(16), Ev3Parameter.constant(0), Ev3Parameter.constant(1), Ev3Parameter.global(0)), parameters(reader));
    }

    @Test
    void shouldEncodeAndDecodeTouchExampleReplyPressed() {
        byte[] documented = hex("07 00 2A 00 02 00 00 80 3F");
        Ev3Reply reply = Ev3Reply.decode(documented);
        assertEquals(0x2A, reply.counter());
        assertEquals(1.0f, reply.dataF(0));
        byte[] globals = new byte[4];
        LittleEndian.putF32(globals, 0, 1.0f);
        assertArrayEquals(documented, Ev3Reply.ok(0x2A, globals).encode());
    }

    @Test
    void shouldEncodeEv3DcDocsStepSpeedThenOutputReadyByteCodes() {
        Ev3Command c = Ev3Command.withReply(0)
                .outputStepSpeed(0x02, 5, 15, 60, 15, MotorState.StopMode.BRAKE)
                .outputReady(0x02).build();
        assertEquals("AE 00 02 05 0F 81 3C 0F 01 AA 00 02", hex(c.code()));
        Ev3CodeReader reader = new Ev3CodeReader(hex("AE:00:02:05:0F:81:3C:0F:01:AA:00:02"), 0, 12);
        assertEquals(Ev3Opcode.OUTPUT_STEP_SPEED.code(), reader.nextByte());
        for (Ev3Parameter p : constants(0, 2, 5, 15, 60, 15, 1)) {
            assertEquals(p, reader.nextParameter());
        }
        assertEquals(Ev3Opcode.OUTPUT_READY.code(), reader.nextByte());
        assertEquals(constants(0, 2), parameters(reader));
    }

    @Test
    void shouldEncodeCComHExampleStartMotorAAtPower20() {
        Ev3Command c = Ev3Command.withoutReply().outputPower(0x01, 20).outputStart(0x01).build();
        assertEquals("0C 00 34 12 80 00 00 A4 00 01 14 A6 00 01", hex(c.encode(0x1234)));
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(c.encode(0x1234));
        assertEquals(Ev3Opcode.OUTPUT_POWER.code(), reader.nextByte());
        assertEquals(constants(0, 1, 20), List.of(reader.nextParameter(), reader.nextParameter(), reader.nextParameter()));
        assertEquals(Ev3Opcode.OUTPUT_START.code(), reader.nextByte());
        assertEquals(constants(0, 1), parameters(reader));
    }

    @Test
    void shouldEncodeCComHExampleStopMotorA() {
        Ev3Command c = Ev3Command.withoutReply().outputStop(0x01, MotorState.StopMode.COAST).build();
        assertEquals("09 00 34 12 80 00 00 A3 00 01 00", hex(c.encode(0x1234)));
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(hex("09 00 34 12 80 00 00 A3 00 01 00"));
        assertEquals(Ev3Opcode.OUTPUT_STOP.code(), reader.nextByte());
        assertEquals(constants(0, 1, 0), parameters(reader));
    }

    @Test
    void shouldEncodeAndDecodeCComHExampleInputRead() {
        Ev3Command c = Ev3Command.withReply(1).inputRead(0, 0, 0, 0).build();
        assertEquals("0B 00 34 12 00 01 00 9A 00 00 00 00 60", hex(c.encode(0x1234)));
        byte[] request = hex("0B 00 34 12 00 01 00 9A 00 00 00 00 60");
        assertEquals(1, Ev3Frame.globalsOf(LittleEndian.u16(request, Ev3Frame.VARS_FIELD_OFFSET)));
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(request);
        assertEquals(Ev3Opcode.INPUT_READ.code(), reader.nextByte());
        assertEquals(List.of(Ev3Parameter.constant(0), Ev3Parameter.constant(0), Ev3Parameter.constant(0), Ev3Parameter.constant(0),
                Ev3Parameter.global(0)), parameters(reader));
        Ev3Reply reply = Ev3Reply.decode(hex("04 00 34 12 02 00"));
        assertEquals(0x1234, reply.counter());
        assertTrue(reply.isOk());
        assertEquals(0, reply.data8(0));
        assertArrayEquals(hex("04 00 34 12 02 00"), Ev3Reply.ok(0x1234, new byte[1]).encode());
    }

    @Test
    void shouldEncodeSpeedPlusStartOnAAndDAtMinus40() {
        Ev3Command c = Ev3Command.withoutReply().outputSpeed(0x09, -40).outputStart(0x09).build();
        assertEquals("0D 00 2C 00 80 00 00 A5 00 09 81 D8 A6 00 09", hex(c.encode(0x2C)));
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(c.encode(0x2C));
        assertEquals(Ev3Opcode.OUTPUT_SPEED.code(), reader.nextByte());
        assertEquals(constants(0, 9, -40), List.of(reader.nextParameter(), reader.nextParameter(), reader.nextParameter()));
        assertEquals(Ev3Opcode.OUTPUT_START.code(), reader.nextByte());
        assertEquals(constants(0, 9), parameters(reader));
    }

    @Test
    void shouldEncodeToneExampleVolume2At440HzFor500Ms() {
        Ev3Command c = Ev3Command.withoutReply().soundTone(2, 440, 500).build();
        assertEquals("0E 00 30 00 80 00 00 94 01 02 82 B8 01 82 F4 01", hex(c.encode(0x30)));
        Ev3CodeReader reader = Ev3CodeReader.ofCommand(c.encode(0x30));
        assertEquals(Ev3Opcode.SOUND.code(), reader.nextByte());
        assertEquals(constants(Ev3Subcode.TONE.code(), 2, 440, 500), parameters(reader));
    }

    @Test
    void shouldDecodeBareErrorReplyOfMalformedHeader() {
        Ev3Reply reply = Ev3Reply.decode(hex("03 00 2A 00 04"));
        assertFalse(reply.isOk());
        assertEquals(0x2A, reply.counter());
        assertEquals(0, reply.globals().length);
        assertArrayEquals(hex("03 00 2A 00 04"), Ev3Reply.error(0x2A, new byte[0]).encode());
    }

    @Test
    void shouldDecodeVmErrorReplyWithItsGlobals() {
        Ev3Reply reply = Ev3Reply.decode(hex("07 00 2B 00 04 68 01 00 00"));
        assertFalse(reply.isOk());
        assertEquals(360, reply.data32(0));
    }

    @Test
    void shouldEncodeBatteryAndCountsOfSeveralMotorsIntoSeparateGlobals() {
        Ev3Command c = Ev3Command.withReply(8).outputGetCount(1, 0).outputGetCount(2, 4).build();
        assertEquals("0D 00 01 00 00 08 00 B3 00 01 60 B3 00 02 64", hex(c.encode(1)));
        assertEquals("81 01 60", hex(Ev3Command.withReply(4).uiReadVbatt(0).build().code()));
        assertEquals("opOUTPUT_GET_COUNT on output B, opOUTPUT_GET_COUNT on output C", c.describe());
    }

    // ---- edge cases ----

    @Test
    void shouldRejectPartialReplyFrameNamingBothLengths() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Ev3Reply.decode(hex("07 00 2B 00 02 68 01")));
        assertTrue(e.getMessage().contains("announces 7") && e.getMessage().contains("5 are there"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> Ev3Reply.decode(hex("03 00 2B")));
    }

    @Test
    void shouldRejectReplyOfAnotherType() {
        assertThrows(IllegalArgumentException.class, () -> Ev3Reply.decode(hex("03 00 2B 00 03")));
    }

    @Test
    void shouldAcceptMaximumGlobals() {
        Ev3Command c = Ev3Command.withReply(Ev3Frame.MAX_GLOBALS).outputGetCount(0, Ev3Frame.MAX_GLOBALS - 4).build();
        byte[] frame = c.encode(7);
        assertEquals("FD 03", hex(new byte[]{frame[5], frame[6]}));
        assertEquals(1021, Ev3Frame.globalsOf(LittleEndian.u16(frame, Ev3Frame.VARS_FIELD_OFFSET)));
        assertTrue(hex(c.code()).endsWith("E2 F9 03"), hex(c.code()));
    }

    @Test
    void shouldRejectOneGlobalMoreThanTheMaximum() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Ev3Command.withReply(1022));
        assertTrue(e.getMessage().contains("globals=1022"), e.getMessage());
    }

    @Test
    void shouldDecodeReplyCarryingMaximumGlobals() {
        byte[] globals = new byte[Ev3Frame.MAX_GLOBALS];
        LittleEndian.putU32(globals, Ev3Frame.MAX_GLOBALS - 4, -5);
        byte[] frame = Ev3Reply.ok(9, globals).encode();
        assertEquals(1026, frame.length);
        assertEquals("00 04", hex(new byte[]{frame[0], frame[1]}));
        assertEquals(-5, Ev3Reply.decode(frame).data32(Ev3Frame.MAX_GLOBALS - 4));
        assertThrows(IllegalArgumentException.class, () -> Ev3Reply.ok(9, new byte[Ev3Frame.MAX_GLOBALS + 1]));
    }

    @Test
    void shouldPackLocalsAboveGlobalsInVars() {
        assertEquals(63 << 10 | 1021, Ev3Frame.vars(63, 1021));
        assertEquals(63, Ev3Frame.localsOf(Ev3Frame.vars(63, 1021)));
        byte[] frame = Ev3Command.withReply(4).locals(2).outputGetCount(0, 0).build().encode(0);
        assertEquals("04 08", hex(new byte[]{frame[Ev3Frame.VARS_FIELD_OFFSET], frame[Ev3Frame.VARS_FIELD_OFFSET + 1]}));
        assertThrows(IllegalArgumentException.class, () -> Ev3Frame.vars(64, 0));
    }

    @Test
    void shouldRejectResultBeyondReservedGlobals() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Ev3Command.withReply(4).outputGetCount(0, 4));
        assertTrue(e.getMessage().contains("global offset 4") && e.getMessage().contains("reserves 4"), e.getMessage());
    }

    @Test
    void shouldRejectCommandWithoutByteCodes() {
        assertThrows(IllegalArgumentException.class, () -> Ev3Command.withReply(0).build());
    }

    @Test
    void shouldAcceptCommandOfMaximumLengthAndRejectOneByteMore() {
        Ev3Command.Builder b = Ev3Command.withoutReply();
        for (int i = 0; i < 1016; i++) {
            b.op(Ev3Opcode.NOP);
        }
        assertEquals(1021, Ev3Frame.length(b.build().encode(0)));
        b.op(Ev3Opcode.NOP);
        assertEquals(1022, Ev3Frame.length(b.build().encode(0)));
        b.op(Ev3Opcode.NOP);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, b::build);
        assertTrue(e.getMessage().contains("length=1023"), e.getMessage());
    }

    @Test
    void shouldRejectSpeedBeyondHundredPercent() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Ev3Command.withoutReply().outputSpeed(1, 101));
        assertTrue(e.getMessage().contains("speed=101"), e.getMessage());
    }

    @Test
    void shouldRejectCounterBeyondSixteenBits() {
        assertThrows(IllegalArgumentException.class, () -> Ev3Command.withoutReply().outputStart(1).build().encode(0x10000));
    }

    @Test
    void shouldNameOpcodesForMessages() {
        assertEquals("opOUTPUT_STEP_SPEED", Ev3Opcode.describe(0xAE));
        assertEquals("opcode 0xFE", Ev3Opcode.describe(0xFE));
        assertEquals("B+C", Ev3Ports.outputNames(0x06));
        assertEquals("S4", Ev3Ports.inputName(3));
        assertEquals("motor B", Ev3Ports.inputName(17));
    }
}
