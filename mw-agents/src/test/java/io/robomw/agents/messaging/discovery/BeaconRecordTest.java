package io.robomw.agents.messaging.discovery;

import org.junit.jupiter.api.Test;

import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The beacon's wire format: what is written is read back; lists too long for a datagram are cut and say so; bad beacons are refused naming the sender. */
class BeaconRecordTest {

    @Test
    void aRecordReadsBackAsWritten() {
        BeaconRecord r = new BeaconRecord("nxt", true, 1000, "nxt", "rmi://127.0.0.1:1099/nxt", List.of("tcp://127.0.0.1:7000"),
                List.of("cmd"), List.of("news", "pose"), List.of("nxt"), false);
        byte[] bytes = r.encode();
        assertTrue(new String(bytes, StandardCharsets.UTF_8).startsWith("robomw-beacon 1\nnode nxt\nstatus online\nperiod-ms 1000\n"));
        assertEquals(r, BeaconRecord.decode(bytes, "test"));
    }

    @Test
    void longListsAreCutToOneDatagramAndSaySo() {
        List<String> topics = new ArrayList<>();
        for (int i = 0; i < 2000; i++) {
            topics.add("a/rather/long/topic/name/number/" + i);
        }
        byte[] bytes = new BeaconRecord("busy", true, 1000, null, null, List.of(), topics, List.of(), List.of(), false).encode();
        assertTrue(bytes.length <= BeaconRecord.MAX_BYTES, "one datagram: " + bytes.length);
        BeaconRecord read = BeaconRecord.decode(bytes, "test");
        assertTrue(read.truncated());
        assertTrue(read.listens().size() > 50 && read.listens().size() < 2000, "as many as fit: " + read.listens().size());
    }

    @Test
    void badBeaconsAreRefusedNamingTheSenderAndTheProblem() {
        for (String[] bad : new String[][] {
                {"hello", "not a RoboMW beacon of version 1"},
                {"robomw-beacon 2\nnode x\n", "not a RoboMW beacon of version 1"},
                {"robomw-beacon 1\nnode x\nstatus online\n", "beacon without period-ms"},
                {"robomw-beacon 1\nnode x\nstatus maybe\nperiod-ms 1000\n", "neither online nor offline"},
                {"robomw-beacon 1\nnode x\nstatus online\nperiod-ms -5\n", "is not 1 to 3600000"},
                {"robomw-beacon 1\nnode x\nstatus online\nperiod-ms 1000\ncolour blue\n", "unknown beacon key 'colour'"},
                {"robomw-beacon 1\nnode x\nstatus online\nperiod-ms 1000\nhost lonely\n", "not 'host NAME ADDRESS'"},
                {"robomw-beacon 1\nnodex\n", "is not 'KEY VALUE'"},
                {"robomw-beacon 1\nnode x\nstatus online\nperiod-ms 1000\nlistens \n", "line 5 ('listens') has no value"},
                {"robomw-beacon 1\nnode x\nstatus online\nperiod-ms 1000\nrobot r\r\n", "line 5 ('robot') has a carriage return in its value"},
                {"robomw-beacon 1\nnode x\r\nstatus online\nperiod-ms 1000\n", "line 2 ('node') has a carriage return"},
                {"robomw-beacon 1\nnode x\nstatus online\nperiod-ms 1000", "cut short: its last line, 4, does not end with a line break"},
                {"robomw-beacon 1\nnode x\nstatus online\nperiod-ms \u0661\u0660\u0660\u0660\n", "is not a number"}}) {
            IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                    () -> BeaconRecord.decode(bad[0].getBytes(StandardCharsets.UTF_8), "peer 127.0.0.1:5000"), bad[0]);
            assertTrue(e.getMessage().startsWith("peer 127.0.0.1:5000: ") && e.getMessage().contains(bad[1]), e.getMessage());
        }
        assertThrows(IllegalArgumentException.class, () -> BeaconRecord.decode(new byte[BeaconRecord.MAX_BYTES + 1], "big"));
    }

    @Test
    void bytesThatAreNotUtf8AreRefusedNamingTheSender() {
        byte[] bytes = "robomw-beacon 1\nnode x\nstatus online\nperiod-ms 1000\nrobot ?\n".getBytes(StandardCharsets.UTF_8);
        bytes[bytes.length - 2] = (byte) 0xFF;

        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> BeaconRecord.decode(bytes, "peer 127.0.0.1:5000"));

        assertEquals("peer 127.0.0.1:5000: not a RoboMW beacon (its bytes are not UTF-8 text)", e.getMessage());
    }

    @Test
    void aBeaconThatFillsADatagramIsWrittenBackWhole() {
        StringBuilder text = new StringBuilder("robomw-beacon 1\nnode full\nstatus online\nperiod-ms 1000\n");
        for (int i = 0; text.length() + 40 < BeaconRecord.MAX_BYTES; i++) {
            text.append("listens topic/").append(String.format("%020d", i)).append('\n');
        }
        while (text.length() < BeaconRecord.MAX_BYTES) {
            text.insert(text.indexOf("node full") + "node full".length(), 'l');
        }
        byte[] bytes = text.toString().getBytes(StandardCharsets.UTF_8);
        assertEquals(BeaconRecord.MAX_BYTES, bytes.length);

        BeaconRecord read = BeaconRecord.decode(bytes, "test");

        assertEquals(read, BeaconRecord.decode(read.encode(), "test"), "not cut: nothing was left out");
        assertEquals(text.toString(), new String(read.encode(), StandardCharsets.UTF_8));
    }
}
