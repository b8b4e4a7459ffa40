package io.robomw.console.rosbridge.graph;

import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;

/** A publication is encoded once per wire form, and in a client's own spelling of the topic when it differs. */
class PublicationTest {

    private static Publication hello() {
        ObjectNode m = JsonNodeFactory.instance.objectNode();
        m.put("data", "hello");
        return new Publication("/chatter", m, 0);
    }

    @Test
    void theJsonFrameIsWrittenOnceForEveryClient() {
        Publication p = hello();
        String first = p.jsonFrame();
        assertEquals("{\"op\":\"publish\",\"topic\":\"/chatter\",\"msg\":{\"data\":\"hello\"}}", first);
        assertSame(first, p.jsonFrame("/chatter"));
        assertSame(first, p.jsonFrame());
        assertSame(p.cborFrame(), p.cborFrame("/chatter"));
    }

    @Test
    void aClientThatNamedTheTopicWithoutTheSlashGetsItsOwnSpelling() {
        assertEquals("{\"op\":\"publish\",\"topic\":\"chatter\",\"msg\":{\"data\":\"hello\"}}", hello().jsonFrame("chatter"));
    }
}
