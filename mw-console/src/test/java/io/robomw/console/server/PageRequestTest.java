package io.robomw.console.server;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class PageRequestTest {

    @Test
    void aRetractNamesItsAgentAndCarriesTokenAndId() throws Exception {
        UUID id = UUID.randomUUID();
        PageRequest r = PageRequest.parse("{\"op\":\"retract\",\"agent\":\"" + id + "\",\"token\":\"t\",\"id\":7}");
        assertEquals(PageRequest.Op.RETRACT, r.op());
        assertEquals(id, r.agent());
        assertEquals("t", r.token());
        assertEquals(7, r.id());
    }

    @Test
    void aStopNamesItsRobot() throws Exception {
        PageRequest r = PageRequest.parse("{\"op\":\"stop\",\"robot\":\"nxt\"}");
        assertEquals("nxt", r.robot());
        assertEquals("", r.token());
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', value = {
            "not json at all|not JSON",
            "[1,2]|a request is a JSON object, got array",
            "{}|field 'op' is missing",
            "{\"op\":5}|field 'op' must be a string, got number",
            "{\"op\":\"format-disk\"}|unknown op 'format-disk'",
            "{\"op\":\"retract\"}|field 'agent' is missing",
            "{\"op\":\"retract\",\"agent\":\"../../etc\"}|must be an agent's id (a UUID)",
            "{\"op\":\"stop\",\"robot\":\"\"}|field 'robot' must name a robot",
            "{\"op\":\"stop\",\"robot\":\"a\",\"id\":\"x\"}|field 'id' must be a whole number"})
    void malformedRequestsAreRefusedSayingWhatIsWrong(String text, String expected) {
        PageRequest.BadRequest e = assertThrows(PageRequest.BadRequest.class, () -> PageRequest.parse(text));
        assertTrue(e.getMessage().contains(expected), e.getMessage());
    }

    @Test
    void anOverlongRequestIsRefusedBeforeParsing() {
        String text = "{\"op\":\"stop\",\"robot\":\"" + "x".repeat(PageRequest.MAX_LENGTH) + "\"}";
        PageRequest.BadRequest e = assertThrows(PageRequest.BadRequest.class, () -> PageRequest.parse(text));
        assertTrue(e.getMessage().contains("limit is " + PageRequest.MAX_LENGTH), e.getMessage());
    }
}
