package io.robomw.platform;

import com.code_intelligence.jazzer.junit.FuzzTest;
import io.robomw.api.RobotException;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.ev3.Ev3Brick;
import io.robomw.platform.ev3.Ev3Command;
import io.robomw.platform.ev3.Ev3Reply;
import io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram;
import io.robomw.platform.ft.txt.TxtController;
import io.robomw.platform.ft.txt.TxtProtocol;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.nxt.NxtBrick;
import io.robomw.platform.nxt.NxtTelegram;
import io.robomw.platform.rcx.RcxBrick;
import io.robomw.platform.rcx.RcxPacket;
import io.robomw.platform.testkit.ScriptedLink;

import java.io.IOException;
import java.time.Duration;
import java.util.Arrays;
import java.util.List;

/**
 * Fuzz tests of what the drivers read from a brick (docs/fuzzing.md): any bytes as everything an
 * NXT, EV3, TXT, Intelligent Interface or RCX (its IR tower) sends back, read by the driver's own brick class over a
 * link that serves them. A driver may refuse what it reads only with an {@link IOException} (the
 * link failed, lost its framing, or the reply did not come) or a {@link RobotException} (the brick
 * answered an error), both naming what was wrong; anything else (an index out of bounds, a
 * negative length) is a finding.
 */
class BrickRepliesFuzzTest {

    private static final Duration REPLY_TIMEOUT = Duration.ofMillis(1);

    private static BrickChannel channel(byte[] bytes) throws IOException {
        // The far end sends the bytes and then nothing, at once: a silent brick times out without waiting.
        Communicator c = new Communicator(new ScriptedLink().named("fuzzed brick").timingOutAtOnce().deliver(bytes));
        c.open();
        return new BrickChannel("fuzzbot", c, REPLY_TIMEOUT);
    }

    @FuzzTest
    void nxtReply(byte[] bytes) throws IOException {
        NxtBrick brick = new NxtBrick("fuzzbot", channel(bytes));
        try {
            brick.request(NxtTelegram.getInputValues(0), 16, 0);
            brick.requestAll(List.of(new NxtBrick.Request(NxtTelegram.resetMotorPosition(true, 1, false), NxtTelegram.STATUS_REPLY, 1), new NxtBrick.Request(NxtTelegram.playTone(true, 440, 10), NxtTelegram.STATUS_REPLY, -1)));
        } catch (IOException | RobotException refused) {
            // the documented refusal
        }
    }

    @FuzzTest
    void ev3Reply(byte[] bytes) throws IOException {
        Ev3Brick brick = new Ev3Brick("fuzzbot", channel(bytes));
        try {
            Ev3Reply r = brick.request(Ev3Command.withReply(4).outputGetCount(0, 0).build());
            r.data32(0);
        } catch (IOException | RobotException refused) {
            // the documented refusal
        }
        try {
            Ev3Reply.decode(bytes);
        } catch (IllegalArgumentException refused) {
            // the documented refusal
        }
    }

    @FuzzTest
    void txtReply(byte[] bytes) throws IOException {
        TxtController txt = new TxtController("fuzzbot", channel(bytes));
        try {
            txt.open();
        } catch (IOException | RobotException refused) {
            // the documented refusal
        }
        try {
            TxtProtocol.Status.decode(bytes);
        } catch (IllegalArgumentException refused) {
            // the documented refusal
        }
    }

    /** What the TXT's emulator decodes: a configuration request (the driver encodes them). */
    @FuzzTest
    void txtConfig(byte[] bytes) {
        try {
            TxtProtocol.Config c = TxtProtocol.Config.decode(bytes);
            if (!TxtProtocol.Config.decode(c.encode()).equals(c)) {
                throw new AssertionError("a configuration does not survive its own encoding: " + c);
            }
        } catch (IllegalArgumentException refused) {
            // the documented refusal
        }
    }

    @FuzzTest
    void intelligentInterfaceReply(byte[] bytes) {
        if (bytes.length == 3) {
            int value = IntelligentInterfaceTelegram.analog(bytes);
            if (value < 0 || value > 1023) {
                throw new AssertionError("an analog reading outside 0..1023: " + value);
            }
        }
    }

    /**
     * What an RCX's IR tower delivers: the echo of each packet (a tower that echoes) and the
     * brick's reply, read by {@link RcxBrick} as the driver's exchanges do (the battery, a
     * sensor's value, the firmware's versions, alive), behind a tower that echoes and one that
     * does not; and the bytes as one packet, which must survive its own encoding when accepted.
     */
    @FuzzTest
    void rcxReply(byte[] bytes) throws IOException {
        for (boolean echo : new boolean[] {true, false}) {
            RcxBrick brick = new RcxBrick("fuzzbot", channel(bytes), echo);
            try {
                brick.batteryMillivolts();
                brick.request(RcxPacket.GET_VALUE, RcxPacket.getValue(RcxPacket.SOURCE_SENSOR_VALUE, 0)).s16();
                RcxPacket.Decoded versions = brick.request(RcxPacket.GET_VERSIONS, RcxPacket.VERSIONS_KEY);
                if (versions.data().length != RcxPacket.replyDataLength(RcxPacket.GET_VERSIONS)) {
                    throw new AssertionError("a reply to Get versions with " + versions.data().length + " data bytes");
                }
                brick.alive();
            } catch (IOException | RobotException refused) {
                // the documented refusal
            }
        }
        try {
            RcxPacket.Decoded p = RcxPacket.decode(bytes);
            if (!Arrays.equals(RcxPacket.encode(p.opcode(), p.data()), bytes)) {
                throw new AssertionError("an RCX packet does not survive its own encoding: " + RcxPacket.hex(bytes));
            }
        } catch (IllegalArgumentException refused) {
            // the documented refusal
        }
    }
}
