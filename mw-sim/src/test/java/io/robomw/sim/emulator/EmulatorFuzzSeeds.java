package io.robomw.sim.emulator;

import io.robomw.platform.ev3.Ev3Command;
import io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram;
import io.robomw.platform.ft.txt.TxtProtocol;
import io.robomw.platform.nxt.NxtTelegram;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

/**
 * Writes the seed inputs of the emulators' and the drivers' fuzz tests (docs/fuzzing.md): what
 * each driver sends (its own encoders), and what each emulator answers to it (framed as on the
 * link), which is what a driver reads from a brick. Run it from mw-sim when a protocol changes:
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
                NxtTelegram.withLengthPrefix(NxtTelegram.setOutputState(true, 1, 75, 0x07, 0x01, 0, 0x20, 360)),
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
