package io.robomw.agents.host;

import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Frame;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.api.AgentStatus;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.EnumSource;

import java.io.IOException;
import java.nio.ByteBuffer;
import java.util.List;
import java.util.Map;
import java.util.UUID;

import static java.util.Map.entry;
import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Every enum that goes on the hosts' wire travels as the code its table gives (checked against
 * the tables, not against the encoder), comes back as itself, and an unknown code is an error
 * naming the code, never an index out of bounds.
 */
class WireCodesTest {

    // The tables of Session, AgentEvent, AgentImage and Bodies, written out again.
    private static final Map<Op, Integer> OPS = Map.ofEntries(entry(Op.TRANSFER, 0), entry(Op.PUT_ARCHIVE, 1), entry(Op.LIST, 2), entry(Op.EVENT, 3),
            entry(Op.MESSAGE, 4), entry(Op.RETRACT, 5), entry(Op.DISPOSE, 6), entry(Op.DESCRIBE, 7), entry(Op.WATCH, 8), entry(Op.OWED, 9),
            entry(Op.DROP_OWED, 10), entry(Op.ARRIVALS, 11));
    private static final Map<Reply.Status, Integer> STATUSES = Map.ofEntries(entry(Reply.Status.OK, 0), entry(Reply.Status.NEED_ARCHIVE, 1),
            entry(Reply.Status.DUPLICATE, 2), entry(Reply.Status.REFUSED, 3), entry(Reply.Status.MOVED, 4), entry(Reply.Status.GONE, 5),
            entry(Reply.Status.NOT_HANDLED, 6), entry(Reply.Status.UNKNOWN_SESSION, 7));
    private static final Map<AgentEvent.Kind, Integer> EVENT_KINDS = Map.of(AgentEvent.Kind.ARRIVED, 0, AgentEvent.Kind.REPORT, 1,
            AgentEvent.Kind.RESULT, 2, AgentEvent.Kind.FAILED, 3, AgentEvent.Kind.DISPOSED, 4, AgentEvent.Kind.VISITS, 5);
    private static final Map<AgentImage.Kind, Integer> IMAGE_KINDS = Map.of(AgentImage.Kind.TRIP, 0, AgentImage.Kind.HOMECOMING, 1);
    private static final Map<AgentStatus, Integer> AGENT_STATUSES = Map.of(AgentStatus.CREATED, 0, AgentStatus.ACTIVE, 1,
            AgentStatus.IN_TRANSIT, 2, AgentStatus.COMPLETED, 3, AgentStatus.DISPOSED, 4, AgentStatus.RETRACTED, 5, AgentStatus.FAILED, 6);

    private static final UUID ID = UUID.fromString("01234567-89ab-cdef-0123-456789abcdef");
    private static final CodeArchive.Digest DIGEST = new CodeArchive.Digest(new byte[CodeArchive.Digest.LENGTH]);

    @ParameterizedTest
    @EnumSource(Op.class)
    void everyOperationIsSealedAsItsCodeAndReadBack(Op op) {
        Session session = new Session(42, new byte[32]);
        Frame frame = Frame.of(new byte[] {9});
        session.seal(7, op.code(), frame);
        assertEquals(OPS.get(op), frame.bytes[16] & 0xFF, "the operation byte follows the session id and sequence");
        assertTrue(session.verifyRequest(frame.bytes));
        assertEquals(op, Op.fromCode(frame.bytes[16] & 0xFF));
    }

    @ParameterizedTest
    @EnumSource(Reply.Status.class)
    void everyReplyStatusIsSentAsItsCodeAndReadBack(Reply.Status status) {
        Session session = new Session(42, new byte[32]);
        byte[] reply = session.reply(3, Reply.of(status, "why"));
        assertEquals(STATUSES.get(status), reply[0] & 0xFF);
        Reply back = session.verifyReply(3, reply);
        assertEquals(status, back.status());
        assertEquals("why", back.text());
    }

    @ParameterizedTest
    @EnumSource(AgentEvent.Kind.class)
    void everyEventKindIsEncodedAsItsCodeAndDecoded(AgentEvent.Kind kind) {
        byte[] bytes = new AgentEvent(ID, 5, kind, "rmi://127.0.0.1:1/a", new byte[] {1, 2}).encode();
        assertEquals(EVENT_KINDS.get(kind), bytes[24] & 0xFF, "the kind byte follows the id and the sequence");
        AgentEvent back = AgentEvent.decode(bytes);
        assertEquals(kind, back.kind());
        assertEquals(5, back.seq());
        assertEquals("rmi://127.0.0.1:1/a", back.location());
        assertArrayEquals(new byte[] {1, 2}, back.payload());
    }

    @ParameterizedTest
    @EnumSource(AgentImage.Kind.class)
    void everyImageKindIsTheLowBitsOfTheFirstByteWithTheFromHomeFlag(AgentImage.Kind kind) {
        for (boolean fromHome : new boolean[] {false, true}) {
            byte[] bytes = new AgentImage(ID, 3, kind, fromHome, "rmi://127.0.0.1:1/home", DIGEST, 2, new byte[] {7}).encode();
            assertEquals(IMAGE_KINDS.get(kind) | (fromHome ? 0x40 : 0), bytes[0] & 0xFF);
            AgentImage back = AgentImage.decode(bytes);
            assertEquals(kind, back.kind());
            assertEquals(fromHome, back.fromHome());
            assertEquals(3, back.hop());
        }
    }

    @Test
    void everyAgentStatusIsListedAsItsCodeAndReadBack() throws IOException {
        List<AgentInfo> agents = AGENT_STATUSES.keySet().stream()
                .map(s -> new AgentInfo(UUID.randomUUID(), "a.B", s, 4, "rmi://127.0.0.1:1/home")).toList();
        byte[] body = Bodies.listReply(agents);
        int at = 4;
        for (AgentInfo a : agents) {
            at += 16 + 2 + a.className().length();
            assertEquals(AGENT_STATUSES.get(a.status()), body[at] & 0xFF, "status of " + a);
            at += 1 + 8 + 2 + a.home().length();
        }
        assertEquals(body.length, at);
        assertEquals(agents, Bodies.readListReply(body, "rmi://127.0.0.1:1/h"));
    }

    @Test
    void unknownOperationCodeNamesTheCode() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Op.fromCode(200));
        assertTrue(e.getMessage().contains("unknown operation code 200"), e.getMessage());
    }

    @Test
    void replyWithAnUnknownStatusCodeIsRefusedNamingTheCode() {
        Session session = new Session(42, new byte[32]);
        byte[] reply = session.reply(3, 200, new byte[0]);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> session.verifyReply(3, reply));
        assertTrue(e.getMessage().contains("unknown reply status code 200"), e.getMessage());
    }

    @Test
    void eventWithAnUnknownKindIsRefusedNamingTheCode() {
        byte[] bytes = new AgentEvent(ID, 1, AgentEvent.Kind.REPORT, "x", new byte[0]).encode();
        bytes[24] = (byte) 0xF0;
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> AgentEvent.decode(bytes));
        assertTrue(e.getMessage().contains("unknown event kind code 240"), e.getMessage());
    }

    @Test
    void imageWithAnUnknownKindOrStrayFlagBitsIsRefusedNamingTheByte() {
        byte[] bytes = new AgentImage(ID, 1, AgentImage.Kind.TRIP, false, "h", DIGEST, 1, new byte[0]).encode();
        bytes[0] = 0x0F;
        IllegalArgumentException kind = assertThrows(IllegalArgumentException.class, () -> AgentImage.decode(bytes));
        assertTrue(kind.getMessage().contains("unknown agent image kind code 15"), kind.getMessage());
        bytes[0] = (byte) 0x80;
        IllegalArgumentException flags = assertThrows(IllegalArgumentException.class, () -> AgentImage.decode(bytes));
        assertTrue(flags.getMessage().contains("first byte 0x80"), flags.getMessage());
    }

    @Test
    void listReplyWithAnUnknownStatusCodeIsRefusedNamingTheHostAndTheCode() {
        byte[] body = Bodies.listReply(List.of(new AgentInfo(ID, "a.B", AgentStatus.ACTIVE, 1, "h")));
        body[4 + 16 + 2 + 3] = 99;
        IOException e = assertThrows(IOException.class, () -> Bodies.readListReply(body, "rmi://127.0.0.1:9/far"));
        assertTrue(e.getMessage().contains("rmi://127.0.0.1:9/far") && e.getMessage().contains("unknown agent status code 99"), e.getMessage());
    }

    @Test
    void listReplyCutShortOrClaimingTooManyAgentsIsRefusedNamingTheHost() {
        byte[] body = Bodies.listReply(List.of(new AgentInfo(ID, "a.B", AgentStatus.ACTIVE, 1, "h")));
        IOException cut = assertThrows(IOException.class, () -> Bodies.readListReply(java.util.Arrays.copyOf(body, body.length - 1), "far"));
        assertTrue(cut.getMessage().contains("host far") && cut.getMessage().contains("cut short"), cut.getMessage());
        byte[] many = ByteBuffer.allocate(4).putInt(Integer.MAX_VALUE).array();
        IOException claim = assertThrows(IOException.class, () -> Bodies.readListReply(many, "far"));
        assertTrue(claim.getMessage().contains("claiming 2147483647 agents"), claim.getMessage());
    }

    @Test
    void messageBodyFlagIsZeroOrOneAndAnythingElseIsRefused() {
        byte[] twoWay = Bodies.message(ID, false, new byte[] {5});
        byte[] oneWay = Bodies.message(ID, true, new byte[] {5});
        assertEquals(0, twoWay[16]);
        assertEquals(1, oneWay[16]);
        assertFalse(Bodies.readMessage(twoWay).oneway());
        assertTrue(Bodies.readMessage(oneWay).oneway());
        oneWay[16] = 2;
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Bodies.readMessage(oneWay));
        assertTrue(e.getMessage().contains("unknown one-way flag 2"), e.getMessage());
        IllegalArgumentException shortBody = assertThrows(IllegalArgumentException.class, () -> Bodies.readMessage(new byte[10]));
        assertTrue(shortBody.getMessage().contains("10 bytes"), shortBody.getMessage());
    }

    @Test
    void unknownSessionReplyIsTheOneByteStatusAPeerRecognisesWithoutAMac() {
        HostEndpoint endpoint = new HostEndpoint("h", ClusterKey.fromPassphrase("k"), (peer, op, m, o, l) -> Reply.ok());
        byte[] call = new byte[Session.HEADER + Session.MAC];
        byte[] reply = endpoint.call(call);
        assertArrayEquals(new byte[] {7}, reply);
        assertTrue(Session.isUnknownSession(reply));
        assertFalse(Session.isUnknownSession(new Session(1, new byte[32]).reply(1, Reply.of(Reply.Status.UNKNOWN_SESSION, ""))),
                "a MAC'd reply is a reply, not the unknown-session answer");
    }
}
