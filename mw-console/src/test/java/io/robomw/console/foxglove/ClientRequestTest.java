package io.robomw.console.foxglove;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A client's text messages, read strictly; a bad one is refused saying what is wrong. */
class ClientRequestTest {

    @Test
    void subscribeKeepsTheClientsOwnIds() throws Exception {
        ClientRequest r = ClientRequest.parse("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":42,\"channelId\":1},{\"id\":4294967295,\"channelId\":2}]}");
        assertEquals(new ClientRequest.Subscribe(List.of(new ClientRequest.Subscription(42, 1), new ClientRequest.Subscription(4294967295L, 2))), r);
    }

    @Test
    void unsubscribeListsSubscriptionIds() throws Exception {
        assertEquals(new ClientRequest.Unsubscribe(List.of(42L, 7L)), ClientRequest.parse("{\"op\":\"unsubscribe\",\"subscriptionIds\":[42,7]}"));
    }

    @Test
    void advertiseAsFoxglovesTeleopSendsIt() throws Exception {
        ClientRequest r = ClientRequest.parse("{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/robots/nxt/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/Twist\"}]}");
        assertEquals(new ClientRequest.Advertise(List.of(new ClientRequest.ClientChannel(1, "/robots/nxt/cmd_vel", "json", "geometry_msgs/Twist"))), r);
    }

    @Test
    void unadvertiseListsChannelIds() throws Exception {
        assertEquals(new ClientRequest.Unadvertise(List.of(1L)), ClientRequest.parse("{\"op\":\"unadvertise\",\"channelIds\":[1]}"));
    }

    @Test
    void opsOfCapabilitiesNotOfferedAreAnsweredAsTheSdkAnswersThem() throws Exception {
        assertEquals("Server does not support parameters capability",
                assertInstanceOf(ClientRequest.Unsupported.class, ClientRequest.parse("{\"op\":\"getParameters\",\"parameterNames\":[]}")).answer());
        assertEquals("Server does not support connection graph capability",
                assertInstanceOf(ClientRequest.Unsupported.class, ClientRequest.parse("{\"op\":\"subscribeConnectionGraph\"}")).answer());
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
            "{oops                                                        | Invalid message: not JSON",
            "[1,2]                                                        | Invalid message: a text message is a JSON object",
            "{\"subscriptions\":[]}                                       | Invalid message: no \"op\"",
            "{\"op\":7}                                                   | Invalid message: no \"op\"",
            "{\"op\":\"dance\"}                                           | Invalid message: unknown op \"dance\"",
            "{\"op\":\"subscribe\"}                                       | Invalid message: subscribe needs an array \"subscriptions\", got none",
            "{\"op\":\"subscribe\",\"subscriptions\":{}}                  | Invalid message: subscribe needs an array",
            "{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":1}]}        | Invalid message: an entry of subscribe has no \"channelId\"",
            "{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":-1,\"channelId\":1}]} | Invalid message: subscribe \"id\" must be an integer from 0 to 4294967295, got -1",
            "{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":4294967296,\"channelId\":1}]} | must be an integer from 0 to 4294967295, got 4294967296",
            "{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":1.5,\"channelId\":1}]} | must be an integer from 0 to 4294967295, got 1.5",
            "{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":\"1\",\"channelId\":1}]} | must be an integer from 0 to 4294967295, got \"1\"",
            "{\"op\":\"subscribe\",\"subscriptions\":[3]}                 | Invalid message: each entry of subscribe is an object, got 3",
            "{\"op\":\"unsubscribe\",\"subscriptionIds\":[\"x\"]}         | Invalid message: unsubscribe subscriptionIds must be an integer",
            "{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/t\",\"encoding\":\"json\"}]} | Invalid message: a channel of advertise needs a string \"schemaName\", got none",
    })
    void aBadMessageIsRefusedSayingWhatIsWrong(String text, String expected) {
        ClientRequest.BadRequest e = assertThrows(ClientRequest.BadRequest.class, () -> ClientRequest.parse(text));
        assertTrue(e.getMessage().contains(expected), "'" + e.getMessage() + "' should contain '" + expected + "'");
    }

    @Test
    void tooManyEntriesAtOnceAreRefused() {
        StringBuilder ids = new StringBuilder();
        for (int i = 0; i <= ClientRequest.MAX_ENTRIES; i++) {
            ids.append(i == 0 ? "" : ",").append(i);
        }
        ClientRequest.BadRequest e = assertThrows(ClientRequest.BadRequest.class,
                () -> ClientRequest.parse("{\"op\":\"unsubscribe\",\"subscriptionIds\":[" + ids + "]}"));
        assertTrue(e.getMessage().contains("carries 1001 entries"), e.getMessage());
    }

    @Test
    void aLongBadValueIsQuotedShortly() {
        String junk = "x".repeat(5000);
        ClientRequest.BadRequest e = assertThrows(ClientRequest.BadRequest.class, () -> ClientRequest.parse("{\"op\":\"" + junk + "\"}"));
        assertTrue(e.getMessage().length() < 300, e.getMessage());
    }
}
