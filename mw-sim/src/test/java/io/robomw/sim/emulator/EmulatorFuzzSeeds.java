package io.robomw.sim.emulator;

import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.platform.aibo.UrbiProtocol;
import io.robomw.platform.ev3.Ev3Command;
import io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram;
import io.robomw.platform.ft.txt.TxtProtocol;
import io.robomw.platform.nxt.NxtTelegram;
import io.robomw.platform.rcx.RcxPacket;
import io.robomw.sim.emulator.aibo.AiboEmulator;
import io.robomw.sim.legged.Quadruped;
import io.robomw.sim.legged.UrbiKernel;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.OptionalDouble;

/**
 * Writes the seed inputs of the emulators' and the drivers' fuzz tests (docs/fuzzing.md): what
 * each driver sends (its own encoders), and what each emulator answers to it (framed as on the
 * link), which is what a driver reads from a brick; the same for the Aibo's URBI server (the
 * simulator's {@code UrbiKernel}) and its driver's decoder. Run it from mw-sim when a protocol changes:
 * {@code java -cp ... io.robomw.sim.emulator.EmulatorFuzzSeeds src/test/resources ../mw-platform/src/test/resources}.
 */
public final class EmulatorFuzzSeeds {

    private EmulatorFuzzSeeds() {
    }

    public static void main(String[] args) throws IOException {
        Path simResources = Path.of(args.length > 0 ? args[0] : "src/test/resources");
        Path platformResources = Path.of(args.length > 1 ? args[1] : "../mw-platform/src/test/resources");
        write("nxt", EmulatorRequestsFuzzTest.nxt(), List.of(
                NxtTelegram.withLengthPrefix(NxtTelegram.getInputValues(0)),
                NxtTelegram.withLengthPrefix(NxtTelegram.setOutputState(true, io.robomw.platform.nxt.OutputState.running(1, 75, io.robomw.platform.nxt.OutputState.Regulation.SPEED, 360))),
                NxtTelegram.withLengthPrefix(NxtTelegram.getOutputState(2)),
                NxtTelegram.withLengthPrefix(NxtTelegram.lsWrite(true, 3, 1, (byte) 0x02, (byte) 0x42)),
                NxtTelegram.withLengthPrefix(NxtTelegram.getBatteryLevel())),
                simResources, "nxtRequest", platformResources, "nxtReply");
        write("ev3", EmulatorRequestsFuzzTest.ev3(), List.of(
                lengthPrefixed(Ev3Command.withReply(4).outputGetCount(0, 0).build().encode(0x2A)),
                lengthPrefixed(Ev3Command.withoutReply().soundTone(2, 440, 500).build().encode(0x2B))),
                simResources, "ev3Request", platformResources, "ev3Reply");
        write("txt", EmulatorRequestsFuzzTest.txt(), List.of(TxtProtocol.queryStatus(), TxtProtocol.startOnline(), TxtProtocol.stopOnline()),
                simResources, "txtRequest", platformResources, "txtReply");
        write("ii", EmulatorRequestsFuzzTest.intelligentInterface(), List.of(
                IntelligentInterfaceTelegram.request(IntelligentInterfaceTelegram.DIGITAL, 0),
                IntelligentInterfaceTelegram.request(IntelligentInterfaceTelegram.ANALOG_EX, IntelligentInterfaceTelegram.withMotor(0, 1,
                        IntelligentInterfaceTelegram.CW))),
                simResources, "intelligentInterfaceRequest", platformResources, "intelligentInterfaceReply");
        write("rcx", EmulatorRequestsFuzzTest.rcx(), List.of(
                RcxPacket.encode(RcxPacket.ALIVE),
                RcxPacket.encode(RcxPacket.ALIVE | RcxPacket.TOGGLE),
                RcxPacket.encode(RcxPacket.GET_VERSIONS, RcxPacket.VERSIONS_KEY),
                RcxPacket.encode(RcxPacket.SET_SENSOR_TYPE, RcxPacket.setSensorType(0, RcxPacket.TYPE_ROTATION)),
                RcxPacket.encode(RcxPacket.SET_SENSOR_MODE, RcxPacket.setSensorMode(0, RcxPacket.MODE_ANGLE)),
                RcxPacket.encode(RcxPacket.SET_MOTOR_POWER, RcxPacket.setMotorPower(RcxPacket.MOTOR_A | RcxPacket.MOTOR_C, 7)),
                RcxPacket.encode(RcxPacket.SET_MOTOR_DIRECTION, RcxPacket.setMotorDirection(RcxPacket.MOTOR_A, RcxPacket.FORWARD)),
                RcxPacket.encode(RcxPacket.SET_MOTOR_ON_OFF, RcxPacket.setMotorOnOff(RcxPacket.MOTOR_A | RcxPacket.MOTOR_C, RcxPacket.ON)),
                RcxPacket.encode(RcxPacket.GET_VALUE, RcxPacket.getValue(RcxPacket.SOURCE_SENSOR_VALUE, 0)),
                RcxPacket.encode(RcxPacket.PLAY_TONE, RcxPacket.playTone(440, 50)),
                RcxPacket.encode(RcxPacket.GET_BATTERY),
                RcxPacket.encode(RcxPacket.STOP_ALL_TASKS)),
                simResources, "rcxRequest", platformResources, "rcxReply");
        rcxExchanges(EmulatorRequestsFuzzTest.rcx(), platformResources);
        urbi(simResources, platformResources);
    }

    /**
     * What the Aibo driver sends (UrbiProtocol's encoders) and a person types, for the URBI
     * server's fuzz test, and what the server answers, as the emulator writes it, for the driver's
     * decoder's (with a binary value as URBI's documents show one, and cut into chunks as the
     * network may cut it: the input's last bytes are the chunk sizes and their count).
     */
    private static void urbi(Path simResources, Path platformResources) throws IOException {
        List<byte[]> requests = List.of(
                UrbiProtocol.command("o1", "motoron; robot.watchdogInterval = 0.5"),
                UrbiProtocol.command("c2", "robot.walk(0.5, 0.15)"),
                UrbiProtocol.command("c3", "robot.turn(-1.570796, 1)"),
                UrbiProtocol.read("r4", "distanceNear"),
                UrbiProtocol.stream("s5", "accelX", 50),
                UrbiProtocol.stop("s5"),
                UrbiProtocol.command("c6", "headPan.val = 30 time:400 & headTilt.val = 0 time:400"),
                UrbiProtocol.command("c7", "robot.arc(0.3, 1.5, 0.1)"),
                UrbiProtocol.command("c8", "robot.drive(0.1, 0.5)"),
                UrbiProtocol.command("c9", "robot.stop()"),
                ascii("p: ping; motoroff; motors on; x = 2 * (3 + -1) / 4; // a comment\n"),
                ascii("speaker.val = BIN 4 raw;abcd\n"),
                ascii("c10+end: robot.fly();\nthis is not urbi;\n/* a comment */ r11: robot.maxSpeed;\n"),
                ascii("l1: loop loop ping,\nstop l1,\n"));
        String kernelInputs = "io/robomw/sim/legged/UrbiKernelFuzzTestInputs/urbiRequest";
        ByteArrayOutputStream all = new ByteArrayOutputStream();
        for (int i = 0; i < requests.size(); i++) {
            put(simResources, kernelInputs, "urbi-" + i, requests.get(i));
            all.write(requests.get(i));
        }
        put(simResources, kernelInputs, "urbi-all", all.toByteArray());

        LeggedDrive drive = new RobotDescriptionLoader().load(Path.of("..", "examples", "robots", "aibo.yaml").toAbsolutePath().normalize())
                .leggedDrive().orElseThrow();
        Quadruped dog = new Quadruped(drive, 1);
        long[] nanos = {0};
        UrbiKernel kernel = new UrbiKernel("aibo", dog, d -> OptionalDouble.of(421), () -> nanos[0]);
        ByteArrayOutputStream answers = new ByteArrayOutputStream();
        answers.write(AiboEmulator.line(0, "", UrbiKernel.Kind.SYSTEM, "URBI Kernel version 1.x, emulated by RoboMW"));
        UrbiKernel.Session session = kernel.open("seeds", (millis, tag, kind, text) -> answers.writeBytes(AiboEmulator.line(millis, tag, kind, text)));
        session.submit(all.toByteArray(), 0, all.size());
        for (int step = 0; step < 300; step++) {
            nanos[0] += 10_000_000L;
            dog.advance(0.01);
            kernel.step();
        }
        String replyInputs = "io/robomw/platform/aibo/UrbiRepliesFuzzTestInputs/urbiReply";
        byte[] served = answers.toByteArray();
        put(platformResources, replyInputs, "server-session", withChunks(served));
        put(platformResources, replyInputs, "server-session-cut", withChunks(served, 7, 1, 64, 3));
        ByteArrayOutputStream binary = new ByteArrayOutputStream();
        binary.write(ascii("[00001234:img] BIN 6 raw 2 1\n"));
        binary.write(new byte[] {0, (byte) 0xFF, '\n', '[', 0x7F, '\r'});
        binary.write(AiboEmulator.line(1235, "img", UrbiKernel.Kind.SYSTEM, "end"));
        binary.write(ascii("[00001236] !!! syntax error: x\r\n"));
        put(platformResources, replyInputs, "binary", withChunks(binary.toByteArray()));
        put(platformResources, replyInputs, "binary-cut", withChunks(binary.toByteArray(), 20, 2, 5));
    }

    private static byte[] ascii(String s) {
        return s.getBytes(StandardCharsets.US_ASCII);
    }

    /**
     * @param bytes  what the server sends
     * @param chunks the sizes of the chunks it arrives in, 1 to 256 each, at most 7 (none: one byte at a time)
     * @return the input of UrbiRepliesFuzzTest#urbiReply: the bytes, then the sizes (as Jazzer's
     *         FuzzedDataProvider takes them, from the end) and their count, last
     */
    private static byte[] withChunks(byte[] bytes, int... chunks) {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        out.writeBytes(bytes);
        for (int i = chunks.length - 1; i >= 0; i--) {
            out.write(chunks[i] - 1);
        }
        out.write(chunks.length);
        return out.toByteArray();
    }

    /**
     * What the tower delivers to the driver for BrickRepliesFuzzTest#rcxReply's exchanges, in its
     * order (the battery, sensor S1's value, the versions, alive): with the tower's echo of each
     * packet, and without (a tower that does not echo).
     */
    private static void rcxExchanges(BrickEmulator rcx, Path platformResources) throws IOException {
        List<byte[]> packets = List.of(
                RcxPacket.encode(RcxPacket.GET_BATTERY),
                RcxPacket.encode(RcxPacket.GET_VALUE, RcxPacket.getValue(RcxPacket.SOURCE_SENSOR_VALUE, 0)),
                RcxPacket.encode(RcxPacket.GET_VERSIONS, RcxPacket.VERSIONS_KEY),
                RcxPacket.encode(RcxPacket.ALIVE));
        ByteArrayOutputStream echoed = new ByteArrayOutputStream();
        ByteArrayOutputStream replies = new ByteArrayOutputStream();
        for (byte[] packet : packets) {
            byte[] heard = rcx.handle(packet);
            echoed.write(heard);
            replies.write(heard, packet.length, heard.length - packet.length);
        }
        String dir = "io/robomw/platform/BrickRepliesFuzzTestInputs/rcxReply";
        put(platformResources, dir, "rcx-echo", echoed.toByteArray());
        put(platformResources, dir, "rcx-no-echo", replies.toByteArray());
    }

    private static byte[] lengthPrefixed(byte[] body) {
        return body; // an EV3 command carries its own length field
    }

    private static void write(String name, BrickEmulator emulator, List<byte[]> requests, Path simResources, String requestTarget,
                              Path platformResources, String replyTarget) throws IOException {
        ByteArrayOutputStream all = new ByteArrayOutputStream();
        for (int i = 0; i < requests.size(); i++) {
            byte[] request = requests.get(i);
            all.write(request);
            put(simResources, "io/robomw/sim/emulator/EmulatorRequestsFuzzTestInputs/" + requestTarget, name + "-" + i, request);
            int[] at = {0};
            byte[] frame = emulator.framing().read(n -> {
                if (at[0] + n > request.length) {
                    return null;
                }
                byte[] out = java.util.Arrays.copyOfRange(request, at[0], at[0] + n);
                at[0] += n;
                return out;
            });
            byte[] reply = frame == null ? null : emulator.handle(frame);
            if (reply != null) {
                put(platformResources, "io/robomw/platform/BrickRepliesFuzzTestInputs/" + replyTarget, name + "-" + i, emulator.framing().encode(reply));
            }
        }
        put(simResources, "io/robomw/sim/emulator/EmulatorRequestsFuzzTestInputs/" + requestTarget, name + "-all", all.toByteArray());
    }

    private static void put(Path resources, String dir, String name, byte[] bytes) throws IOException {
        Path d = resources.resolve(dir);
        Files.createDirectories(d);
        Files.write(d.resolve(name), bytes);
    }
}
