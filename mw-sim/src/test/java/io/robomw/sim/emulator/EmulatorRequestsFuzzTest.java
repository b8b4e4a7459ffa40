package io.robomw.sim.emulator;

import com.code_intelligence.jazzer.junit.FuzzTest;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulator;
import io.robomw.sim.emulator.ft.txt.TxtEmulator;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import io.robomw.sim.emulator.rcx.RcxEmulator;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Set;

/**
 * Fuzz tests of what a brick emulator takes from its port (docs/fuzzing.md): any bytes as what
 * arrives on the port of the NXT, EV3, TXT, Intelligent Interface and RCX emulators, each bound to a
 * robot of a simulated world, cut into telegrams by the emulator's own framing as its serving
 * loop does. The framing may refuse bytes as malformed, and an emulator may refuse a telegram
 * with an {@link IllegalArgumentException} naming what is wrong (its loop drops it and goes on);
 * anything else is a finding.
 */
class EmulatorRequestsFuzzTest {

    private static final BrickEmulator NXT;
    private static final BrickEmulator EV3;
    private static final BrickEmulator TXT;
    private static final BrickEmulator INTELLIGENT_INTERFACE;
    private static final BrickEmulator RCX;

    static {
        try {
            Path dir = Files.createTempDirectory("emulator-fuzz");
            Path examples = Path.of("..", "examples", "robots").toAbsolutePath().normalize();
            // a world may name robot files in its own tree only (issue 37): the examples' robot files go beside it
            for (String file : List.of("nxt-two-wheeled.yaml", "ev3-two-wheeled.yaml", "ft-txt.yaml", "ft-intelligent.yaml", "rcx-two-wheeled.yaml")) {
                Files.copy(examples.resolve(file), dir.resolve(file));
            }
            String robots = ".";
            Files.writeString(dir.resolve("world.yaml"), """
                    name: fuzz
                    arena: { width: 10, height: 3 }
                    robots:
                      - { robot: %1$s/nxt-two-wheeled.yaml, name: nxt, x: 1, y: 1.5, heading: 0 }
                      - { robot: %1$s/ev3-two-wheeled.yaml, name: ev3, x: 3, y: 1.5, heading: 0 }
                      - { robot: %1$s/ft-txt.yaml, name: txt, x: 5, y: 1.5, heading: 0 }
                      - { robot: %1$s/ft-intelligent.yaml, name: ii, x: 7, y: 1.5, heading: 0 }
                      - { robot: %1$s/rcx-two-wheeled.yaml, name: rcx, x: 9, y: 1.5, heading: 0 }
                    """.formatted(robots));
            Simulation sim = Simulation.load(dir.resolve("world.yaml"), Set.of("nxt", "ev3", "txt", "ii", "rcx"));
            NXT = new NxtEmulator(motors(sim, "nxt"), sim.world().stepSeconds());
            EV3 = new Ev3Emulator(motors(sim, "ev3"), 0.01);
            TXT = new TxtEmulator(motors(sim, "txt"));
            INTELLIGENT_INTERFACE = new IntelligentInterfaceEmulator(motors(sim, "ii"), sim.world().stepSeconds());
            RCX = new RcxEmulator(motors(sim, "rcx"), sim.world().stepSeconds(), true);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    static BrickEmulator nxt() {
        return NXT;
    }

    static BrickEmulator ev3() {
        return EV3;
    }

    static BrickEmulator txt() {
        return TXT;
    }

    static BrickEmulator intelligentInterface() {
        return INTELLIGENT_INTERFACE;
    }

    static BrickEmulator rcx() {
        return RCX;
    }

    private static SimMotors motors(Simulation sim, String name) {
        return SimMotors.of(sim.world(), name).orElseThrow();
    }

    /** Serves the bytes as the emulator's loop serves its port, up to 64 telegrams. */
    private static void serve(BrickEmulator emulator, byte[] bytes) {
        int[] at = {0};
        Framing.Reader port = n -> {
            if (n < 0 || at[0] + n > bytes.length) {
                return null; // the bytes did not all come
            }
            byte[] out = java.util.Arrays.copyOfRange(bytes, at[0], at[0] + n);
            at[0] += n;
            return out;
        };
        for (int telegrams = 0; telegrams < 64 && at[0] < bytes.length; telegrams++) {
            byte[] frame;
            try {
                frame = emulator.framing().read(port);
            } catch (Framing.MalformedFrameException refused) {
                return;
            } catch (IOException e) {
                throw new AssertionError("reading bytes in memory failed: " + e, e);
            }
            if (frame == null) {
                return;
            }
            try {
                byte[] reply = emulator.handle(frame);
                if (reply != null) {
                    emulator.framing().encode(reply);
                }
            } catch (IllegalArgumentException refused) {
                // the documented refusal: the loop drops the telegram and goes on
            }
        }
    }

    @FuzzTest
    void nxtRequest(byte[] bytes) {
        serve(NXT, bytes);
    }

    /**
     * opOUTPUT_READY holds a direct command until the stepping outputs reach their target: that
     * takes simulated time, which this harness does not run (and for a step of a billion degrees,
     * weeks, as on a real brick), so it would hang the target (the fuzzer found such an input:
     * input {@code ev3-step-then-ready} is one). Its opcode byte, 0xAA, is served as opNOP (0x01)
     * here (no driver of RoboMW sends opOUTPUT_READY; the emulator serves it for other programs).
     */
    @FuzzTest
    void ev3Request(byte[] bytes) {
        byte[] served = bytes.clone();
        for (int i = 0; i < served.length; i++) {
            if (served[i] == (byte) OUTPUT_READY) {
                served[i] = (byte) NOP;
            }
        }
        serve(EV3, served);
    }

    /** EV3 opcodes: opOUTPUT_READY and opNOP (Ev3Opcode's codes). */
    private static final int OUTPUT_READY = 0xAA;
    private static final int NOP = 0x01;

    @FuzzTest
    void txtRequest(byte[] bytes) {
        serve(TXT, bytes);
    }

    @FuzzTest
    void intelligentInterfaceRequest(byte[] bytes) {
        serve(INTELLIGENT_INTERFACE, bytes);
    }

    /** What an RCX hears through its serial IR tower (which echoes every packet before the brick's reply). */
    @FuzzTest
    void rcxRequest(byte[] bytes) {
        serve(RCX, bytes);
    }
}
