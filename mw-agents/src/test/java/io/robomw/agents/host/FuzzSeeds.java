package io.robomw.agents.host;

import io.robomw.agents.host.core.HostActivity;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.wire.WireFrames;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.store.AgentStore;
import io.robomw.agents.host.store.JournalStore;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.security.PayloadAllowList;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.api.AgentStatus;
import io.robomw.api.Itinerary;

import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;

/**
 * Writes the seed inputs of mw-agents' fuzz tests (docs/fuzzing.md): valid encodings made by the
 * encoders, which the fuzzer mutates from, and which the regression run in {@code mvn verify}
 * decodes. Run it from the module directory when a format changes:
 * {@code java -cp target/test-classes:target/classes:... io.robomw.agents.host.FuzzSeeds src/test/resources}.
 */
public final class FuzzSeeds {

    private FuzzSeeds() {
    }

    public static void main(String[] args) throws Exception {
        Path resources = Path.of(args.length > 0 ? args[0] : "src/test/resources");
        UUID id = new UUID(0x1234_5678_9abc_def0L, 0x0fed_cba9_8765_4321L);
        CodeArchive.Digest digest = new CodeArchive.Digest(new byte[CodeArchive.Digest.LENGTH]);
        String home = "rmi://127.0.0.1:1099/home";

        Seeds host = new Seeds(resources, "io.robomw.agents.host.HostDecodersFuzzTest");
        host.write("agentEvent", "report", new AgentEvent(id, 3, AgentEvent.Kind.REPORT, "rmi://127.0.0.1:1100/a", StateCodec.write("at a")).encode());
        host.write("agentEvent", "arrived", new AgentEvent(id, 0, AgentEvent.Kind.ARRIVED, "rmi://127.0.0.1:1100/a", new byte[0]).encode());
        VisitorAgent agent = new VisitorAgent();
        agent.itinerary().addStop("rmi://127.0.0.1:1100/a").addStop(home).repeat(2).retry(3, Duration.ofSeconds(1));
        agent.itinerary().record("rmi://127.0.0.1:1100/a", Itinerary.Outcome.FAILED, "java.lang.IllegalStateException: x\n\tat a.B.c(B.java:1)");
        byte[] state = StateCodec.write(agent);
        host.write("agentImage", "trip", new AgentImage(id, 2, AgentImage.Kind.TRIP, true, home, digest, 4, state).encode());
        host.write("agentImage", "homecoming", new AgentImage(id, 9, AgentImage.Kind.HOMECOMING, false, home, digest, 1, new byte[0]).encode());
        host.write("hostDescription", "full", new HostDescription("a", "rmi://127.0.0.1:1100/a", "nxt", List.of("tcp://127.0.0.1:7000"),
                List.of(new HostDescription.Known("b", "rmi://127.0.0.1:1101/b"))).encode());

        List<byte[]> bodies = List.of(
                Bodies.listReply(List.of(new AgentInfo(id, "a.B", AgentStatus.ACTIVE, 3, home))),
                Bodies.owedReply(List.of(new OwedDelivery(id, 4, "RESULT", home, Instant.ofEpochMilli(1_700_000_000_000L), 2, "refused"))),
                Bodies.dropOwed(OwedSelector.home(home)),
                Bodies.visits(agent.itinerary().history()),
                Bodies.message(id, true, StateCodec.write("hello")),
                Bodies.agentRequest(id),
                new byte[CodeArchive.Digest.LENGTH + 4],
                Bodies.owedEvent(home, new AgentEvent(id, 5, AgentEvent.Kind.RESULT, "rmi://127.0.0.1:1100/a", StateCodec.write(42))));
        for (int i = 0; i < bodies.size(); i++) {
            host.write("bodies", "layout-" + i, withTrailingByte(bodies.get(i), i)); // the last byte picks the reader
        }
        host.write("hostCalls", "list", withTrailingByte(new byte[0], Op.LIST.code()));
        host.write("hostCalls", "event", withTrailingByte(new AgentEvent(id, 1, AgentEvent.Kind.DISPOSED, "x", new byte[0]).encode(), Op.EVENT.code()));
        host.write("hostCalls", "drop-owed", withTrailingByte(Bodies.dropOwed(OwedSelector.all()), Op.DROP_OWED.code()));
        host.write("hostCalls", "transfer", withTrailingByte(new AgentImage(id, 1, AgentImage.Kind.TRIP, false, home, digest, 1, state).encode(),
                Op.TRANSFER.code()));
        byte[] transfer = new AgentImage(id, 1, AgentImage.Kind.TRIP, false, home, digest, 1, state).encode();
        host.write("wireFrames", "hello-transfer", new WireScript.Builder().frame(3, WireFrames.OP_HELLO, true, 1, 0, 0, new byte[0])
                .frame(3, Op.TRANSFER.code(), true, 2, 0, 0, transfer).build());
        host.write("wireFrames", "hello-list-unknown-op", new WireScript.Builder().frame(3, WireFrames.OP_HELLO, true, 1, 0, 0, new byte[0])
                .frame(3, Op.LIST.code(), true, 2, 0, 0, new byte[0]).frame(3, 99, true, 3, 0, 0, new byte[0]).build());
        host.write("wireFrames", "replay", new WireScript.Builder().frame(3, WireFrames.OP_HELLO, true, 5, 0, 0, new byte[0])
                .frame(3, WireFrames.OP_HELLO, true, 5, 0, 0, new byte[0]).build());
        host.write("wireFrames", "wrong-tag", new WireScript.Builder().frame(3, WireFrames.OP_HELLO, true, 1, 1, 0, new byte[0]).build());
        host.write("wireFrames", "lying-length", new WireScript.Builder().frame(3, WireFrames.OP_HELLO, true, 1, 0, 0, new byte[0])
                .frame(3, Op.TRANSFER.code(), true, 2, 2, 3, new byte[] {1, 2, 3}).build());
        host.write("wireFrames", "unknown-session", new WireScript.Builder().frame(3, WireFrames.OP_HELLO, false, 1, 0, 0, new byte[0]).build());
        host.write("wireFrames", "raw-header", new WireScript.Builder().raw(new byte[] {3, 64, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0}).build());
        host.write("endpoint", "auth", withTrailingByte(ByteBuffer.allocate(2 + 4 + 96).putShort((short) 4).put("peer".getBytes()).array(), 102));

        new Seeds(resources, "io.robomw.agents.host.code.AgentStateFuzzTest").write("state", "visitor", state);
        new Seeds(resources, "io.robomw.agents.host.code.AgentStateFuzzTest").write("state", "itinerary", StateCodec.write(agent.itinerary()));
        // the form hosts send agents in (StateCodec.COMPACT_MAGIC): class descriptors as name and fingerprint
        java.io.ByteArrayOutputStream compact = new java.io.ByteArrayOutputStream();
        new StateCodec(List.of(), 1 << 20).writeCompact(agent, compact);
        new Seeds(resources, "io.robomw.agents.host.code.AgentStateFuzzTest").write("state", "visitor-compact", compact.toByteArray());

        Path journalDir = Files.createTempDirectory("journal-seed");
        try (JournalStore s = JournalStore.open(journalDir)) {
            byte[] image = new AgentImage(id, 2, AgentImage.Kind.TRIP, false, home, digest, 4, state).encode();
            s.accepted(id, 2, image, 0, image.length);
            s.started(id, 2);
            s.eventPending(new AgentStore.PendingEvent(id, 4, 1_700_000_000_000L, Bodies.owedEvent(home, new AgentEvent(id, 4, AgentEvent.Kind.REPORT, "a", new byte[3]))));
            s.eventDelivered(id, 4);
            s.departing(id, 3, image, 0, image.length);
            s.departed(id, 3);
        }
        byte[] journal = Files.readAllBytes(journalDir.resolve("journal"));
        new Seeds(resources, "io.robomw.agents.host.store.JournalFuzzTest").write("replay", "every-record", journal);

        Seeds frames = new Seeds(resources, "io.robomw.agents.messaging.frame.MessageFramesFuzzTest");
        PayloadCodec payloads = new PayloadCodec(PayloadAllowList.jdkDefaults(), FuzzSeeds.class.getClassLoader());
        PayloadCodec.Encoded text = payloads.encode("hello");
        byte[] frame = FrameCodec.encode(new Frame(FrameKind.PUBLISH, 5, 0x1122334455667788L, 9, new UUID(1, 2), 1_000_000L, "a", "b", "t", "f",
                text.type(), text.bytes(), false), false);
        frames.write("frame", "publish", frame);
        byte[] head = FrameCodec.encode(new Frame(FrameKind.PUBLISH_SHARED, 0, 0x1122334455667788L, 9, new UUID(1, 2), 1_000_000L, "a", "", "t", "f",
                1, new byte[0], false), false);
        frames.write("apartHead", "head", io.robomw.agents.messaging.mqtt.ApartHead.encode(head).getBytes(java.nio.charset.StandardCharsets.US_ASCII));
        byte[] twice = new byte[frame.length * 2];
        System.arraycopy(frame, 0, twice, 0, frame.length);
        System.arraycopy(frame, 0, twice, frame.length, frame.length);
        frames.write("stream", "two-frames", twice);
        for (Object value : List.of("hello", 42, 7L, 2.5, 1.5f, true, new byte[] {1, 2}, new ArrayList<>(List.of("a", "b")))) {
            PayloadCodec.Encoded e = payloads.encode((java.io.Serializable) value);
            frames.write("payload", "type-" + e.type() + "-" + value.getClass().getSimpleName(), withTrailingByte(e.bytes(), e.type()));
        }
        frames.write("presence", "host", new io.robomw.agents.messaging.PresenceRecord("a", true, Instant.parse("2026-11-24T10:15:30.123Z"),
                Instant.parse("2026-11-24T10:15:29.870Z"), "mw-a-1",
                86_400, List.of("tcp://127.0.0.1:7000"), "a", "rmi://127.0.0.1:1100/a", List.of("nxt"),
                List.of(id + " io.robomw.examples.Patrol ACTIVE")).encode());
        frames.write("beacon", "node-with-host", new io.robomw.agents.messaging.discovery.BeaconRecord("nxt", true, 1000, "nxt",
                "rmi://127.0.0.1:1099/nxt", List.of("tcp://127.0.0.1:7000", "udp://127.0.0.1:7001"), List.of("cmd"), List.of("news", "pose"),
                List.of("nxt"), false).encode());
        frames.write("beacon", "offline", new io.robomw.agents.messaging.discovery.BeaconRecord("mw-cli-42", false, 1000, null, null,
                List.of("tcp://127.0.0.1:7002"), List.of(), List.of(), List.of(), false).encode());
        List<String> topics = new ArrayList<>();
        for (int i = 0; i < 400; i++) {
            topics.add("a/rather/long/topic/name/number/" + i);
        }
        frames.write("beacon", "truncated", new io.robomw.agents.messaging.discovery.BeaconRecord("busy", true, 1000, null, null, List.of(), topics,
                List.of(), List.of(), false).encode());

        HostActivity activity = new HostActivity();
        activity.record(id, "io.robomw.examples.Patrol", HostActivity.ARRIVED, "rmi://127.0.0.1:1100/a", "hop 2 from b");
        activity.record(id, "io.robomw.examples.Patrol", HostActivity.REPORT, "rmi://127.0.0.1:1100/a", "at a");
        host.write("watch", "activity", activity.watchReply("a", "nxt", List.of(), 0));
    }

    private static byte[] withTrailingByte(byte[] body, int last) {
        byte[] out = java.util.Arrays.copyOf(body, body.length + 1);
        out[body.length] = (byte) last;
        return out;
    }

    /** Where a fuzz test class's seeds go: {@code <resources>/<package>/<Class>Inputs/<method>/<name>}, as Jazzer reads them. */
    record Seeds(Path resources, String testClass) {
        void write(String method, String name, byte[] bytes) throws IOException {
            Path dir = resources.resolve(testClass.replace('.', '/') + "Inputs").resolve(method);
            Files.createDirectories(dir);
            Files.write(dir.resolve(name), bytes);
        }
    }
}
