package io.robomw.console.rosbridge.protocol;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import com.fasterxml.jackson.dataformat.cbor.databind.CBORMapper;
import io.robomw.console.rosbridge.graph.Topic;
import io.robomw.console.rosbridge.msg.Wire;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Every op of the rosbridge v2 protocol as one client sees it, and the traps: no status before
 * set_level, the connection goes on after bad input, ids echoed, both type spellings.
 */
class ClientSessionTest {

    private static final ObjectMapper JSON = new ObjectMapper();

    /** JSON with ' for ", so the tests read like the frames. */
    private static String q(String s) {
        return s.replace('\'', '"');
    }

    private static JsonNode parse(String s) throws Exception {
        return JSON.readTree(s);
    }

    @Test
    void aClientGetsWhatItPublishesOnATopicItSubscribedTo() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'advertise','id':'advertise:/chatter:1','type':'std_msgs/msg/String','topic':'/chatter','latch':false,'queue_size':100}"));
            w.send(q("{'op':'subscribe','id':'subscribe:/chatter:2','type':'std_msgs/String','topic':'/chatter','compression':'none','throttle_rate':0,'queue_length':0}"));
            w.send(q("{'op':'publish','id':'publish:/chatter:3','topic':'/chatter','msg':{'data':'hello'},'latch':false}"));
            assertEquals(q("{'op':'publish','topic':'/chatter','msg':{'data':'hello'}}"), w.transport.next());
            assertTrue(w.transport.drain().isEmpty(), "no status frames: the client did not ask for them");
        }
    }

    @Test
    void publishingWithoutAdvertisingAdvertisesWithTheTopicsType() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'subscribe','id':'s1','topic':'/chatter'}"));
            w.send(q("{'op':'publish','topic':'/chatter','msg':{'data':'x'}}"));
            assertEquals("x", parse(w.transport.next()).at("/msg/data").asText());
            assertTrue(w.graph.topic("/chatter").orElseThrow().publishers().contains("/rosbridge_websocket"));
        }
    }

    @Test
    void publishingOnATopicNoOneDeclaredIsRefusedAndTheConnectionGoesOn() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'publish','topic':'/nowhere','msg':{'data':'x'}}"));
            assertTrue(w.transport.drain().isEmpty(), "refused without a status frame: the client did not ask for them");
            w.send(q("{'op':'set_level','level':'error'}"));
            w.send(q("{'op':'publish','id':'p7','topic':'/nowhere','msg':{'data':'x'}}"));
            JsonNode status = parse(w.transport.next());
            assertEquals("status", status.get("op").asText());
            assertEquals("error", status.get("level").asText());
            assertEquals("p7", status.get("id").asText());
            assertTrue(status.get("msg").asText().contains("Cannot infer topic type for topic /nowhere"), status.toString());
            w.send(q("{'op':'call_service','id':'c1','service':'/echo','args':{'data':true}}"));
            assertEquals(q("{'op':'service_response','service':'/echo','values':{'success':true,'message':'echo'},'result':true,'id':'c1'}"),
                    w.transport.next());
        }
    }

    @Test
    void unknownOpsBadJsonAndMessagesWithoutAnOpGetAStatusErrorOnlyAfterSetLevel() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send("{not json");
            w.send(q("{'op':'auth','mac':'x'}"));
            w.send(q("{'id':'x'}"));
            w.send("[1,2,3]");
            w.send(q("{'op':'advertise_service','service':'/mine','type':'std_srvs/srv/Trigger'}"));
            assertTrue(w.transport.drain().isEmpty());
            w.send(q("{'op':'set_level','level':'error','id':'lvl'}"));
            w.send("{not json");
            assertTrue(parse(w.transport.next()).get("msg").asText().startsWith("Unable to parse message as JSON"));
            w.send(q("{'op':'auth','id':'a1','mac':'x'}"));
            JsonNode unknown = parse(w.transport.next());
            assertTrue(unknown.get("msg").asText().startsWith("Unknown operation: auth. Allowed operations: [advertise, unadvertise, publish"), unknown.toString());
            assertTrue(unknown.get("msg").asText().contains("token in the URL"), unknown.toString());
            assertEquals("a1", unknown.get("id").asText());
            w.send(q("{'id':'x'}"));
            assertTrue(parse(w.transport.next()).get("msg").asText().startsWith("Received a message without an op"));
            w.send(q("{'op':'advertise_service','service':'/mine','type':'std_srvs/srv/Trigger'}"));
            assertTrue(parse(w.transport.next()).get("msg").asText().startsWith("advertise_service is not offered by this bridge"));
            w.send(q("{'op':'set_level','level':'none'}"));
            w.send("{not json");
            w.send(q("{'op':'call_service','id':'c2','service':'/echo','args':{'data':false}}"));
            assertEquals("service_response", parse(w.transport.next()).get("op").asText(), "status is off again; the connection goes on");
        }
    }

    @Test
    void infoStatusComesOnlyAtInfoLevel() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'set_level','level':'info'}"));
            w.send(q("{'op':'subscribe','id':'s1','topic':'/chatter'}"));
            JsonNode info = parse(w.transport.next());
            assertEquals("info", info.get("level").asText());
            assertEquals("Subscribed to /chatter", info.get("msg").asText());
            w.send(q("{'op':'set_level','level':'warning'}"));
            w.send(q("{'op':'subscribe','id':'s2','topic':'/chatter','compression':'png'}"));
            JsonNode warning = parse(w.transport.next());
            assertEquals("warning", warning.get("level").asText());
            assertTrue(warning.get("msg").asText().contains("png compression is not offered"), warning.toString());
            assertTrue(w.transport.drain().isEmpty(), "no info at warning level");
        }
    }

    @Test
    void subscribingToAnUnknownTopicNeedsATypeAndThenDeclaresIt() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'set_level','level':'error'}"));
            w.send(q("{'op':'subscribe','id':'s1','topic':'/later'}"));
            assertTrue(parse(w.transport.next()).get("msg").asText().contains("Cannot infer topic type for topic /later"));
            w.send(q("{'op':'subscribe','id':'s2','topic':'/later','type':'std_msgs/msg/Bool'}"));
            Topic later = w.graph.topic("/later").orElseThrow();
            assertEquals("std_msgs/msg/Bool", later.type().name().full());
            later.publish((ObjectNode) parse("{\"data\":true}"));
            assertEquals(q("{'op':'publish','topic':'/later','msg':{'data':true}}"), w.transport.next());
        }
    }

    @Test
    void aTypeThatDiffersFromTheTopicsIsATypeConflict() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'set_level','level':'error'}"));
            w.send(q("{'op':'subscribe','id':'s1','topic':'/chatter','type':'std_msgs/msg/Bool'}"));
            assertTrue(parse(w.transport.next()).get("msg").asText().contains("already established with type std_msgs/msg/String"));
            w.send(q("{'op':'advertise','id':'a1','topic':'/chatter','type':'std_msgs/msg/Int32'}"));
            assertTrue(parse(w.transport.next()).get("msg").asText().contains("already has type std_msgs/msg/String"));
        }
    }

    @Test
    void unsubscribeWithAnIdEndsThatOneAndWithoutAnIdEndsAll() throws Exception {
        try (Wiring w = new Wiring()) {
            Topic chatter = w.graph.topic("/chatter").orElseThrow();
            w.send(q("{'op':'subscribe','id':'a','topic':'/chatter'}"));
            w.send(q("{'op':'subscribe','id':'b','topic':'/chatter'}"));
            chatter.publish((ObjectNode) parse("{\"data\":\"1\"}"));
            w.transport.next();
            assertTrue(w.transport.drain().isEmpty(), "two subscriptions of one client get each message once");
            w.send(q("{'op':'unsubscribe','id':'a','topic':'/chatter'}"));
            assertTrue(chatter.hasSubscribers());
            w.send(q("{'op':'subscribe','id':'c','topic':'/chatter'}"));
            w.send(q("{'op':'unsubscribe','topic':'/chatter'}"));
            assertFalse(chatter.hasSubscribers());
            chatter.publish((ObjectNode) parse("{\"data\":\"2\"}"));
            assertTrue(w.transport.drain().isEmpty());
        }
    }

    @Test
    void callServiceAnswersWithValuesAndTheCallsId() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'call_service','id':'call_service:/echo:1','service':'/echo','args':{'data':true}}"));
            assertEquals(q("{'op':'service_response','service':'/echo','values':{'success':true,'message':'echo'},'result':true,'id':'call_service:/echo:1'}"),
                    w.transport.next());
            w.send(q("{'op':'call_service','id':5,'service':'/echo','args':[]}"));
            JsonNode r = parse(w.transport.next());
            assertEquals(5, r.get("id").intValue(), "an id that is a number comes back as a number");
            assertFalse(r.at("/values/success").booleanValue(), "[] is no arguments: data false");
            w.send(q("{'op':'call_service','id':'t','service':'/echo','type':'std_srvs/SetBool','args':{}}"));
            assertTrue(parse(w.transport.next()).get("result").booleanValue(), "the type in its short spelling");
        }
    }

    @Test
    void aCallThatCannotBeMadeIsAnsweredResultFalseWithTheReason() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'call_service','id':'c1','service':'/nope','args':{}}"));
            assertEquals(q("{'op':'service_response','service':'/nope','values':'Service /nope does not exist','result':false,'id':'c1'}"), w.transport.next());
            w.send(q("{'op':'call_service','id':'c2','service':'/echo','args':{'data':'yes'}}"));
            JsonNode bad = parse(w.transport.next());
            assertFalse(bad.get("result").booleanValue());
            assertEquals("std_srvs/SetBool_Request message requires a bool for field data, but got a string", bad.get("values").asText());
            w.send(q("{'op':'call_service','id':'c3','service':'/echo','args':{'data':true,'extra':1}}"));
            assertEquals("Message type std_srvs/SetBool_Request does not have a field extra", parse(w.transport.next()).get("values").asText());
            w.send(q("{'op':'call_service','id':'c4','service':'/echo','type':'std_srvs/srv/Trigger','args':{}}"));
            assertTrue(parse(w.transport.next()).get("values").asText().contains("has type std_srvs/srv/SetBool"));
            w.slowAnswer.completeExceptionally(new IllegalStateException("the robot is on fire"));
            w.send(q("{'op':'call_service','id':'c5','service':'/slow'}"));
            assertEquals("the robot is on fire", parse(w.transport.next()).get("values").asText());
        }
    }

    @Test
    void aCallIsAnsweredWhenItsHandlerCompletesWhileOtherWorkGoesOn() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'call_service','id':'slow','service':'/slow'}"));
            w.send(q("{'op':'call_service','id':'fast','service':'/echo','args':{'data':true}}"));
            assertEquals("fast", parse(w.transport.next()).get("id").asText());
            ObjectNode done = JsonNodeFactory.instance.objectNode();
            done.put("success", true);
            w.slowAnswer.complete(done);
            JsonNode slow = parse(w.transport.next());
            assertEquals("slow", slow.get("id").asText());
            assertEquals("", slow.at("/values/message").asText(), "fields the handler left out get their defaults");
        }
    }

    @Test
    void aClientMayHaveOnlySoManyCallsWaiting() throws Exception {
        try (Wiring w = new Wiring(Limits.DEFAULTS.withMaxCallsInFlight(2))) {
            w.send(q("{'op':'call_service','id':'1','service':'/slow'}"));
            w.send(q("{'op':'call_service','id':'2','service':'/slow'}"));
            w.send(q("{'op':'call_service','id':'3','service':'/slow'}"));
            JsonNode third = parse(w.transport.next());
            assertEquals("3", third.get("id").asText());
            assertTrue(third.get("values").asText().contains("already has 2 calls waiting"), third.toString());
            assertEquals(2, w.session.callsInFlight());
            w.slowAnswer.complete(JsonNodeFactory.instance.objectNode());
            assertEquals(0, w.session.callsInFlight());
            assertEquals(List.of("1", "2"), w.transport.drain().stream().map(f -> {
                try {
                    return parse(f.text()).get("id").asText();
                } catch (Exception e) {
                    throw new AssertionError(e);
                }
            }).sorted().toList());
        }
    }

    @Test
    void aCallServiceWithoutAServiceGetsOnlyAStatus() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'call_service','id':'c1','args':{}}"));
            assertTrue(w.transport.drain().isEmpty(), "rosbridge_suite cannot answer it either");
            w.send(q("{'op':'set_level','level':'error'}"));
            w.send(q("{'op':'call_service','id':'c1','args':{}}"));
            assertEquals("call_service: call_service needs a 'service' field", parse(w.transport.next()).get("msg").asText());
        }
    }

    @Test
    void aMessageSentInFragmentsIsHandledWhenWhole() throws Exception {
        try (Wiring w = new Wiring()) {
            String call = q("{'op':'call_service','id':'big','service':'/echo','args':{'data':true}}");
            int cut = call.length() / 3;
            String[] parts = {call.substring(0, cut), call.substring(cut, 2 * cut), call.substring(2 * cut)};
            w.send(Wire.jsonFrame(Map.of("op", "fragment", "id", "f1", "data", parts[2], "num", 2, "total", 3)));
            w.send(Wire.jsonFrame(Map.of("op", "fragment", "id", "f1", "data", parts[0], "num", 0, "total", 3)));
            assertTrue(w.transport.drain().isEmpty());
            w.send(Wire.jsonFrame(Map.of("op", "fragment", "id", "f1", "data", parts[1], "num", 1, "total", 3)));
            assertEquals("big", parse(w.transport.next()).get("id").asText());
        }
    }

    @Test
    void aFragmentSizeCutsWhatTheClientGetsIntoFragmentsThatAddUpToTheFrame() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'subscribe','id':'s','topic':'/chatter','fragment_size':20}"));
            w.graph.topic("/chatter").orElseThrow().publish((ObjectNode) parse("{\"data\":\"a message longer than twenty characters\"}"));
            String whole = q("{'op':'publish','topic':'/chatter','msg':{'data':'a message longer than twenty characters'}}");
            int total = (whole.length() + 19) / 20;
            StringBuilder joined = new StringBuilder();
            for (int i = 0; i < total; i++) {
                JsonNode f = parse(w.transport.next());
                assertEquals("fragment", f.get("op").asText());
                assertEquals(i, f.get("num").intValue());
                assertEquals(total, f.get("total").intValue());
                joined.append(f.get("data").asText());
            }
            assertEquals(whole, joined.toString());
        }
    }

    @Test
    void cborCompressionSendsEachMessageAsOneBinaryFrame() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'subscribe','id':'s','topic':'/chatter','compression':'cbor'}"));
            w.graph.topic("/chatter").orElseThrow().publish((ObjectNode) parse("{\"data\":\"binary\"}"));
            RecordingTransport.Sent f = w.transport.nextFrame();
            assertNotNull(f.binary());
            JsonNode decoded = new CBORMapper().readTree(f.binary());
            assertEquals(parse(q("{'op':'publish','topic':'/chatter','msg':{'data':'binary'}}")), decoded);
        }
    }

    @Test
    void cborRawIsRefusedSayingWhy() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'set_level','level':'error'}"));
            w.send(q("{'op':'subscribe','id':'s','topic':'/chatter','compression':'cbor-raw'}"));
            assertTrue(parse(w.transport.next()).get("msg").asText().contains("cbor-raw carries ROS 2's own serialisation"));
            assertFalse(w.graph.topic("/chatter").orElseThrow().hasSubscribers());
        }
    }

    @Test
    void aBinaryFrameIsReadAsCbor() throws Exception {
        try (Wiring w = new Wiring()) {
            w.session.onBinary(new CBORMapper().writeValueAsBytes(Map.of("op", "call_service", "id", "b", "service", "/echo", "args", Map.of("data", true))));
            assertEquals("b", parse(w.transport.next()).get("id").asText());
        }
    }

    @Test
    void aThrottleWithoutAQueueDropsWhatComesWithinThePeriod() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'subscribe','id':'s','topic':'/chatter','throttle_rate':60000}"));
            Topic chatter = w.graph.topic("/chatter").orElseThrow();
            for (int i = 0; i < 5; i++) {
                chatter.publish((ObjectNode) parse("{\"data\":\"" + i + "\"}"));
            }
            assertEquals("0", parse(w.transport.next()).at("/msg/data").asText(), "the first in the period goes out");
            assertTrue(w.transport.drain().isEmpty(), "the rest of the minute is dropped, as rosbridge_suite's throttle does");
        }
    }

    @Test
    void aThrottleWithAQueueSendsTheQueuedMessagesOnePerPeriod() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'subscribe','id':'s','topic':'/chatter','throttle_rate':50,'queue_length':3}"));
            Topic chatter = w.graph.topic("/chatter").orElseThrow();
            long start = System.nanoTime();
            for (int i = 0; i < 5; i++) {
                chatter.publish((ObjectNode) parse("{\"data\":\"" + i + "\"}"));
            }
            List<String> got = new java.util.ArrayList<>();
            for (int i = 0; i < 4; i++) {
                got.add(parse(w.transport.next()).at("/msg/data").asText());
            }
            assertEquals(List.of("0", "2", "3", "4"), got, "the first goes at once; of the rest the queue of 3 keeps the newest");
            assertTrue(System.nanoTime() - start >= 3 * 50_000_000L, "three more periods passed before the last");
        }
    }

    @Test
    void aSlowClientLosesItsOldestMessagesPerQueueLength() throws Exception {
        try (Wiring w = new Wiring()) {
            w.transport.hold();
            w.send(q("{'op':'subscribe','id':'s','topic':'/chatter','queue_length':2}"));
            Topic chatter = w.graph.topic("/chatter").orElseThrow();
            int n = Outbox.MAX_IN_FLIGHT + 10;
            for (int i = 0; i < n; i++) {
                chatter.publish((ObjectNode) parse("{\"data\":\"" + i + "\"}"));
            }
            w.transport.release();
            List<String> got = w.transport.drain().stream().map(s -> {
                try {
                    return parse(s.text()).at("/msg/data").asText();
                } catch (Exception e) {
                    throw new AssertionError(e);
                }
            }).toList();
            assertEquals(Outbox.MAX_IN_FLIGHT + 2, got.size());
            assertEquals(String.valueOf(Outbox.MAX_IN_FLIGHT - 1), got.get(Outbox.MAX_IN_FLIGHT - 1), "those handed to the connection before it stalled");
            assertEquals(List.of(String.valueOf(n - 2), String.valueOf(n - 1)), got.subList(Outbox.MAX_IN_FLIGHT, got.size()), "then the newest two");
            assertEquals(8, w.outbox.dropped());
        }
    }

    @Test
    void aClientMayHoldOnlySoManySubscriptions() throws Exception {
        try (Wiring w = new Wiring(Limits.DEFAULTS.withMaxSubscriptions(2))) {
            w.send(q("{'op':'set_level','level':'error'}"));
            w.send(q("{'op':'subscribe','id':'1','topic':'/chatter'}"));
            w.send(q("{'op':'subscribe','id':'2','topic':'/chatter'}"));
            w.send(q("{'op':'subscribe','id':'1','topic':'/chatter','throttle_rate':5}"));
            assertTrue(w.transport.drain().isEmpty(), "a subscription given again with its id is changed, not added");
            w.send(q("{'op':'subscribe','id':'3','topic':'/chatter'}"));
            assertTrue(parse(w.transport.next()).get("msg").asText().contains("already has 2 subscriptions"));
        }
    }

    @Test
    void aFieldOfTheWrongKindIsRefusedAsRosbridgesTypeCheckDoes() throws Exception {
        try (Wiring w = new Wiring()) {
            w.send(q("{'op':'set_level','level':'error'}"));
            w.send(q("{'op':'subscribe','id':'s','topic':'/chatter','throttle_rate':'fast'}"));
            assertEquals("subscribe: Expected field throttle_rate to be one of [int] (at least 0). Invalid value: \"fast\"",
                    parse(w.transport.next()).get("msg").asText());
            w.send(q("{'op':'subscribe','id':'s','topic':7}"));
            assertEquals("subscribe: Expected field topic to be one of [str]. Invalid value: 7", parse(w.transport.next()).get("msg").asText());
            w.send(q("{'op':'publish','topic':'/chatter','msg':{'data':5}}"));
            assertEquals("publish: publish on /chatter: std_msgs/String message requires a string for field data, but got an integer (5)",
                    parse(w.transport.next()).get("msg").asText());
        }
    }

    @Test
    void leavingEndsTheClientsSubscriptionsAndAdvertisements() throws Exception {
        Wiring w = new Wiring();
        w.send(q("{'op':'advertise','id':'a','topic':'/mine','type':'std_msgs/msg/Empty'}"));
        w.send(q("{'op':'subscribe','id':'s','topic':'/chatter'}"));
        assertTrue(w.graph.topic("/mine").isPresent());
        w.close();
        assertFalse(w.graph.topic("/chatter").orElseThrow().hasSubscribers());
        assertTrue(w.graph.topic("/mine").isEmpty(), "a topic only this client published on goes with it");
    }
}
