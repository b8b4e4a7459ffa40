package io.robomw.console.mcap;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.node.ArrayNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.UncheckedIOException;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeMap;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * The MCAP project's conformance files (MIT, src/test/resources/mcap-conformance/LICENSE): each
 * reference file {@code NAME.mcap} was written by the reference writers with the features its name
 * lists, and {@code NAME.json} lists its records. The project keeps the .mcap files in Git LFS, so
 * what we have of each is its LFS pointer: size and SHA-256. Our writer, given the listed records
 * and the same features, must write those bytes exactly (same size, same SHA-256); our reader must
 * read them back to the listed records (chunks expanded, message indexes skipped, as the
 * conformance runner's streamed readers do).
 */
class McapConformanceTest {

    private static final ObjectMapper JSON = new ObjectMapper();
    private static final List<String> VARIANTS = List.of("NoData", "NoData-st-sum", "OneMessage", "OneMessage-st-sum",
            "OneMessage-ch-mx", "OneMessage-ch-chx-mx-st-sum", "OneMessage-ch-chx-mx-rch-rsh-st-sum", "OneMessage-ch-rsh-st-sum",
            "OneSchemalessMessage", "OneSchemalessMessage-ch-chx-mx-rch-st-sum", "TenMessages", "TenMessages-ch-chx-mx-rch-rsh-st-sum",
            "TenMessages-ch-mx", "TenMessages-rch-rsh-st-sum", "OneAttachment", "OneAttachment-ax-st-sum", "OneMetadata-mdx-st-sum");

    static Stream<String> variants() {
        return VARIANTS.stream();
    }

    @ParameterizedTest
    @MethodSource("variants")
    void writerWritesTheReferenceBytesFromTheListedRecords(String variant) throws Exception {
        byte[] written = write(variant);
        String pointer = new String(resource(variant + ".mcap.lfs-pointer"), java.nio.charset.StandardCharsets.UTF_8);
        String sha = java.util.HexFormat.of().formatHex(java.security.MessageDigest.getInstance("SHA-256").digest(written));
        assertEquals(pointerField(pointer, "size"), String.valueOf(written.length), variant + ": size");
        assertEquals(pointerField(pointer, "oid").replace("sha256:", ""), sha, variant + ": SHA-256 of the bytes");
    }

    @ParameterizedTest
    @MethodSource("variants")
    void readerReadsTheReferenceBytesToTheListedRecords(String variant) throws IOException {
        List<JsonNode> read = new ArrayList<>();
        try (McapReader reader = new McapReader(new ByteArrayInputStream(write(variant)), variant, McapReader.Options.DEFAULT)) {
            for (McapRecord r; (r = reader.next()) != null; ) {
                if (!(r instanceof McapRecord.MessageIndex)) {
                    read.add(toJson(r));
                }
            }
        }
        JsonNode expected = JSON.readTree(resource(variant + ".json")).get("records");
        assertEquals(expected, JSON.valueToTree(read), variant);
    }

    private static String pointerField(String pointer, String name) {
        return pointer.lines().filter(l -> l.startsWith(name + " ")).findFirst().orElseThrow().substring(name.length() + 1).trim();
    }

    /** Writes a variant from its listed records, with the features its name lists. */
    static byte[] write(String variant) throws IOException {
        Set<String> f = features(variant);
        McapWriter.Options.Builder b = McapWriter.Options.builder();
        Map<String, McapWriter.Feature> byName = Map.of("ch", McapWriter.Feature.CHUNKED, "mx", McapWriter.Feature.MESSAGE_INDEX,
                "chx", McapWriter.Feature.CHUNK_INDEX, "st", McapWriter.Feature.STATISTICS, "sum", McapWriter.Feature.SUMMARY_OFFSETS,
                "rsh", McapWriter.Feature.REPEAT_SCHEMAS, "rch", McapWriter.Feature.REPEAT_CHANNELS, "ax", McapWriter.Feature.ATTACHMENT_INDEX,
                "mdx", McapWriter.Feature.METADATA_INDEX);
        byName.forEach((name, feature) -> {
            if (f.contains(name)) {
                b.with(feature);
            }
        });
        McapWriter.Options options = b.build();
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        McapWriter writer = new McapWriter(bytes, options);
        Map<Integer, Integer> schemaIds = new HashMap<>();
        Map<Integer, Integer> channelIds = new HashMap<>();
        for (JsonNode record : JSON.readTree(resource(variant + ".json")).get("records")) {
            Map<String, JsonNode> fields = fields(record);
            if (record.get("type").asText().equals("DataEnd")) {
                break; // what follows is the summary the writer makes itself
            }
            switch (record.get("type").asText()) {
                case "Header" -> writer.start(fields.get("profile").asText(), fields.get("library").asText());
                case "Schema" -> schemaIds.put(fields.get("id").asInt(),
                        writer.registerSchema(fields.get("name").asText(), fields.get("encoding").asText(), bytes(fields.get("data"))));
                case "Channel" -> {
                    int schema = fields.get("schema_id").asInt();
                    channelIds.put(fields.get("id").asInt(), writer.registerChannel(schema == 0 ? 0 : schemaIds.get(schema), fields.get("topic").asText(),
                            fields.get("message_encoding").asText(), stringMap(fields.get("metadata"))));
                }
                case "Message" -> writer.addMessage(channelIds.get(fields.get("channel_id").asInt()), fields.get("sequence").asLong(),
                        fields.get("log_time").asLong(), fields.get("publish_time").asLong(), bytes(fields.get("data")));
                case "Attachment" -> writer.addAttachment(fields.get("log_time").asLong(), fields.get("create_time").asLong(), fields.get("name").asText(),
                        fields.get("media_type").asText(), bytes(fields.get("data")));
                case "Metadata" -> writer.addMetadata(fields.get("name").asText(), stringMap(fields.get("metadata")));
                default -> {
                    // indexes, statistics, summary offsets, data end and footer: the writer makes its own
                }
            }
        }
        writer.close();
        return bytes.toByteArray();
    }

    private static Set<String> features(String variant) {
        String[] parts = variant.split("-");
        return Set.copyOf(Arrays.asList(parts).subList(1, parts.length));
    }

    static byte[] resource(String name) {
        try (InputStream in = McapConformanceTest.class.getResourceAsStream("/mcap-conformance/" + name)) {
            if (in == null) {
                throw new IllegalStateException("no test resource mcap-conformance/" + name);
            }
            return in.readAllBytes();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private static Map<String, JsonNode> fields(JsonNode record) {
        Map<String, JsonNode> m = new LinkedHashMap<>();
        for (JsonNode pair : record.get("fields")) {
            m.put(pair.get(0).asText(), pair.get(1));
        }
        return m;
    }

    private static byte[] bytes(JsonNode array) {
        byte[] b = new byte[array.size()];
        for (int i = 0; i < b.length; i++) {
            b[i] = (byte) Integer.parseInt(array.get(i).asText());
        }
        return b;
    }

    private static Map<String, String> stringMap(JsonNode object) {
        Map<String, String> m = new LinkedHashMap<>();
        object.fields().forEachRemaining(e -> m.put(e.getKey(), e.getValue().asText()));
        return m;
    }

    /** The conformance runner's form: type, then the fields sorted by their snake_case names, numbers as strings. */
    private static JsonNode toJson(McapRecord r) {
        TreeMap<String, JsonNode> f = new TreeMap<>();
        String type;
        if (r instanceof McapRecord.Header h) {
            type = "Header";
            f.put("profile", s(h.profile()));
            f.put("library", s(h.library()));
        } else if (r instanceof McapRecord.Footer x) {
            type = "Footer";
            f.put("summary_start", n(x.summaryStart()));
            f.put("summary_offset_start", n(x.summaryOffsetStart()));
            f.put("summary_crc", n(Integer.toUnsignedLong(x.summaryCrc())));
        } else if (r instanceof McapRecord.Schema x) {
            type = "Schema";
            f.put("id", n(x.id()));
            f.put("name", s(x.name()));
            f.put("encoding", s(x.encoding()));
            f.put("data", b(x.data()));
        } else if (r instanceof McapRecord.Channel x) {
            type = "Channel";
            f.put("id", n(x.id()));
            f.put("schema_id", n(x.schemaId()));
            f.put("topic", s(x.topic()));
            f.put("message_encoding", s(x.messageEncoding()));
            ObjectNode m = JsonNodeFactory.instance.objectNode();
            x.metadata().forEach(m::put);
            f.put("metadata", m);
        } else if (r instanceof McapRecord.Message x) {
            type = "Message";
            f.put("channel_id", n(x.channelId()));
            f.put("sequence", n(x.sequence()));
            f.put("log_time", n(x.logTime()));
            f.put("publish_time", n(x.publishTime()));
            f.put("data", b(x.data()));
        } else if (r instanceof McapRecord.ChunkIndex x) {
            type = "ChunkIndex";
            f.put("message_start_time", n(x.messageStartTime()));
            f.put("message_end_time", n(x.messageEndTime()));
            f.put("chunk_start_offset", n(x.chunkStartOffset()));
            f.put("chunk_length", n(x.chunkLength()));
            ObjectNode m = JsonNodeFactory.instance.objectNode();
            x.messageIndexOffsets().forEach((k, v) -> m.put(String.valueOf(k), String.valueOf(v)));
            f.put("message_index_offsets", m);
            f.put("message_index_length", n(x.messageIndexLength()));
            f.put("compression", s(x.compression()));
            f.put("compressed_size", n(x.compressedSize()));
            f.put("uncompressed_size", n(x.uncompressedSize()));
        } else if (r instanceof McapRecord.Attachment x) {
            type = "Attachment";
            f.put("log_time", n(x.logTime()));
            f.put("create_time", n(x.createTime()));
            f.put("name", s(x.name()));
            f.put("media_type", s(x.mediaType()));
            f.put("data", b(x.data()));
        } else if (r instanceof McapRecord.AttachmentIndex x) {
            type = "AttachmentIndex";
            f.put("offset", n(x.offset()));
            f.put("length", n(x.length()));
            f.put("log_time", n(x.logTime()));
            f.put("create_time", n(x.createTime()));
            f.put("data_size", n(x.dataSize()));
            f.put("name", s(x.name()));
            f.put("media_type", s(x.mediaType()));
        } else if (r instanceof McapRecord.Statistics x) {
            type = "Statistics";
            f.put("message_count", n(x.messageCount()));
            f.put("schema_count", n(x.schemaCount()));
            f.put("channel_count", n(x.channelCount()));
            f.put("attachment_count", n(x.attachmentCount()));
            f.put("metadata_count", n(x.metadataCount()));
            f.put("chunk_count", n(x.chunkCount()));
            f.put("message_start_time", n(x.messageStartTime()));
            f.put("message_end_time", n(x.messageEndTime()));
            ObjectNode m = JsonNodeFactory.instance.objectNode();
            x.channelMessageCounts().forEach((k, v) -> m.put(String.valueOf(k), String.valueOf(v)));
            f.put("channel_message_counts", m);
        } else if (r instanceof McapRecord.Metadata x) {
            type = "Metadata";
            f.put("name", s(x.name()));
            ObjectNode m = JsonNodeFactory.instance.objectNode();
            x.metadata().forEach(m::put);
            f.put("metadata", m);
        } else if (r instanceof McapRecord.MetadataIndex x) {
            type = "MetadataIndex";
            f.put("offset", n(x.offset()));
            f.put("length", n(x.length()));
            f.put("name", s(x.name()));
        } else if (r instanceof McapRecord.SummaryOffset x) {
            type = "SummaryOffset";
            f.put("group_opcode", n(x.groupOpcode()));
            f.put("group_start", n(x.groupStart()));
            f.put("group_length", n(x.groupLength()));
        } else if (r instanceof McapRecord.DataEnd x) {
            type = "DataEnd";
            f.put("data_section_crc", n(Integer.toUnsignedLong(x.dataSectionCrc())));
        } else {
            throw new AssertionError("unexpected record " + r);
        }
        ObjectNode o = JsonNodeFactory.instance.objectNode();
        o.put("type", type);
        ArrayNode fields = o.putArray("fields");
        f.forEach((k, v) -> fields.addArray().add(k).add(v));
        return o;
    }

    private static JsonNode s(String v) {
        return JsonNodeFactory.instance.textNode(v);
    }

    private static JsonNode n(long v) {
        return JsonNodeFactory.instance.textNode(Long.toUnsignedString(v));
    }

    private static JsonNode b(byte[] data) {
        ArrayNode a = JsonNodeFactory.instance.arrayNode();
        for (byte x : data) {
            a.add(String.valueOf(x & 0xFF));
        }
        return a;
    }
}
