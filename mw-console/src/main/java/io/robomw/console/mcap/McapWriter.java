package io.robomw.console.mcap;

import io.robomw.console.mcap.McapRecord.Attachment;
import io.robomw.console.mcap.McapRecord.AttachmentIndex;
import io.robomw.console.mcap.McapRecord.Channel;
import io.robomw.console.mcap.McapRecord.Chunk;
import io.robomw.console.mcap.McapRecord.ChunkIndex;
import io.robomw.console.mcap.McapRecord.DataEnd;
import io.robomw.console.mcap.McapRecord.Footer;
import io.robomw.console.mcap.McapRecord.Header;
import io.robomw.console.mcap.McapRecord.Message;
import io.robomw.console.mcap.McapRecord.MessageIndex;
import io.robomw.console.mcap.McapRecord.Metadata;
import io.robomw.console.mcap.McapRecord.MetadataIndex;
import io.robomw.console.mcap.McapRecord.Schema;
import io.robomw.console.mcap.McapRecord.Statistics;
import io.robomw.console.mcap.McapRecord.SummaryOffset;

import java.io.IOException;
import java.io.OutputStream;
import java.util.ArrayList;
import java.util.EnumSet;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.zip.CRC32;

/**
 * Writes an MCAP file as a stream: the header, then messages (in chunks, each followed by its
 * message indexes), attachments and metadata as they come, and on {@link #close()} the Data End
 * record, the summary (schemas, channels, statistics, metadata, attachment and chunk indexes,
 * grouped by opcode in that order), the summary offsets and the footer. With every option on (the
 * default, {@link Options#INDEXED}) the file is what Foxglove and the {@code mcap} tools read
 * fastest: chunked and indexed. Chunks are not compressed (compression "").
 *
 * <p>A schema and a channel are written into the data section (inside the chunk, when chunked)
 * just before the first message that needs them, as the reference writers do; ids start at 1.
 * Thread-safe: every method holds the writer's lock. A killed process leaves a file whose whole
 * chunks can still be read from the start ({@link McapReader} with
 * {@link McapReader.Options#tolerant()}); {@link #flushChunk()} bounds what is lost.
 */
public final class McapWriter implements AutoCloseable {

    /** What a writer can write besides the messages: each is in the file only if its options have it. */
    public enum Feature {
        /** Put messages (and their schemas and channels) in chunks. */
        CHUNKED,
        /** A message index per channel after each chunk. */
        MESSAGE_INDEX,
        /** A chunk index per chunk in the summary. */
        CHUNK_INDEX,
        /** A statistics record in the summary. */
        STATISTICS,
        /** Summary offset records for each group. */
        SUMMARY_OFFSETS,
        /** Every schema again in the summary. */
        REPEAT_SCHEMAS,
        /** Every channel again in the summary. */
        REPEAT_CHANNELS,
        /** An attachment index per attachment in the summary. */
        ATTACHMENT_INDEX,
        /** A metadata index per metadata record in the summary. */
        METADATA_INDEX
    }

    /**
     * What to write besides the messages ({@link #builder()}, or {@link #INDEXED}).
     *
     * @param features  what the file has
     * @param chunkSize close a chunk once it holds this many bytes (with {@link Feature#CHUNKED})
     */
    public record Options(Set<Feature> features, long chunkSize) {
        /** The chunk size of {@link #INDEXED} and of a new builder: 1 MiB. */
        public static final long DEFAULT_CHUNK_SIZE = 1 << 20;
        /** Chunked and indexed, 1 MiB chunks: everything Foxglove and the {@code mcap} tools use. */
        public static final Options INDEXED = builder().with(Feature.values()).build();

        /**
         * @param features  what the file has
         * @param chunkSize close a chunk once it holds this many bytes, &gt; 0
         */
        public Options {
            features = features.isEmpty() ? Set.of() : Set.copyOf(EnumSet.copyOf(features));
            if (chunkSize <= 0) {
                throw new IllegalArgumentException("an MCAP chunk size must be > 0 bytes, got " + chunkSize);
            }
        }

        /** @return options without any feature (an unchunked file with no index), 1 MiB chunks, to add to */
        public static Builder builder() {
            return new Builder();
        }

        /** @param feature a feature @return whether these options have it */
        public boolean has(Feature feature) {
            return features.contains(feature);
        }

        /** @param bytes the chunk size @return these options with it */
        public Options withChunkSize(long bytes) {
            return new Options(features, bytes);
        }

        /** Builds {@link Options}: the features to write, and the chunk size. */
        public static final class Builder {
            private final Set<Feature> features = EnumSet.noneOf(Feature.class);
            private long chunkSize = DEFAULT_CHUNK_SIZE;

            private Builder() {
            }

            /** @param more features to write @return this */
            public Builder with(Feature... more) {
                features.addAll(List.of(more));
                return this;
            }

            /** @param bytes close a chunk once it holds this many bytes @return this */
            public Builder chunkSize(long bytes) {
                this.chunkSize = bytes;
                return this;
            }

            /** @return the options */
            public Options build() {
                return new Options(features, chunkSize);
            }
        }
    }

    private final OutputStream out;
    private final Options options;
    private final LeWriter buffer = new LeWriter(4096);
    private final LeWriter chunk = new LeWriter(64 * 1024);
    private final CRC32 dataCrc = new CRC32();
    private final Map<Integer, Schema> schemas = new LinkedHashMap<>();
    private final Map<Integer, Channel> channels = new LinkedHashMap<>();
    private final Set<Integer> writtenSchemas = new LinkedHashSet<>();
    private final Set<Integer> writtenChannels = new LinkedHashSet<>();
    private final Map<Integer, List<long[]>> chunkMessageIndex = new LinkedHashMap<>();
    private final List<ChunkIndex> chunkIndexes = new ArrayList<>();
    private final List<AttachmentIndex> attachmentIndexes = new ArrayList<>();
    private final List<MetadataIndex> metadataIndexes = new ArrayList<>();
    private final Map<Integer, Long> channelMessageCounts = new LinkedHashMap<>();
    private long position;
    private int nextSchemaId = 1;
    private int nextChannelId = 1;
    private long messageCount;
    private long attachmentCount;
    private long metadataCount;
    private long chunkCount;
    private long messageStart;
    private long messageEnd;
    private int chunkMessages;
    private long chunkStart;
    private long chunkEnd;
    private boolean started;
    private boolean closed;

    /**
     * @param out     where the file goes (closed with this writer); buffer it
     * @param options what to write
     */
    public McapWriter(OutputStream out, Options options) {
        this.out = out;
        this.options = options;
    }

    /**
     * Writes the magic and the header.
     *
     * @param profile the profile ("" for none)
     * @param library the writer's name and version
     * @throws IOException if the stream fails
     */
    public synchronized void start(String profile, String library) throws IOException {
        if (started) {
            throw new IllegalStateException("this MCAP writer has already started");
        }
        started = true;
        buffer.raw(Mcap.MAGIC);
        RecordCodec.write(new Header(profile, library), buffer);
        emit(true);
    }

    /**
     * Registers a schema; it is written before the first message of a channel that uses it.
     *
     * @return its id
     */
    public synchronized int registerSchema(String name, String encoding, byte[] data) {
        int id = nextSchemaId++;
        schemas.put(id, new Schema(id, name, encoding, data.clone()));
        return id;
    }

    /**
     * Registers a channel; it is written before its first message.
     *
     * @param schemaId its schema, or 0 for none
     * @return its id
     */
    public synchronized int registerChannel(int schemaId, String topic, String messageEncoding, Map<String, String> metadata) {
        if (schemaId != 0 && !schemas.containsKey(schemaId)) {
            throw new IllegalArgumentException("no schema " + schemaId + " was registered for channel '" + topic + "'");
        }
        if (nextChannelId > 0xFFFF) {
            throw new IllegalStateException("an MCAP file holds at most 65535 channels");
        }
        int id = nextChannelId++;
        channels.put(id, new Channel(id, schemaId, topic, messageEncoding, metadata));
        return id;
    }

    /**
     * Adds a message.
     *
     * @param channelId   a registered channel
     * @param sequence    a counter (u32)
     * @param logTime     when it was recorded, ns
     * @param publishTime when it was published, ns
     * @param data        the encoded message
     * @throws IOException if the stream fails
     */
    public synchronized void addMessage(int channelId, long sequence, long logTime, long publishTime, byte[] data) throws IOException {
        requireOpen();
        Channel channel = channels.get(channelId);
        if (channel == null) {
            throw new IllegalArgumentException("no channel " + channelId + " was registered");
        }
        if (messageCount == 0 || Long.compareUnsigned(logTime, messageStart) < 0) {
            messageStart = logTime;
        }
        if (messageCount == 0 || Long.compareUnsigned(logTime, messageEnd) > 0) {
            messageEnd = logTime;
        }
        messageCount++;
        channelMessageCounts.merge(channelId, 1L, Long::sum);
        LeWriter target = options.has(Feature.CHUNKED) ? chunk : buffer;
        if (!writtenChannels.contains(channelId)) {
            if (channel.schemaId() != 0 && writtenSchemas.add(channel.schemaId())) {
                RecordCodec.write(schemas.get(channel.schemaId()), target);
            }
            if (options.has(Feature.CHUNKED) && options.has(Feature.MESSAGE_INDEX)) {
                chunkMessageIndex.computeIfAbsent(channelId, k -> new ArrayList<>());
            }
            RecordCodec.write(channel, target);
            writtenChannels.add(channelId);
        }
        if (options.has(Feature.CHUNKED)) {
            if (chunkMessages == 0 || Long.compareUnsigned(logTime, chunkStart) < 0) {
                chunkStart = logTime;
            }
            if (chunkMessages == 0 || Long.compareUnsigned(logTime, chunkEnd) > 0) {
                chunkEnd = logTime;
            }
            chunkMessages++;
            if (options.has(Feature.MESSAGE_INDEX)) {
                chunkMessageIndex.computeIfAbsent(channelId, k -> new ArrayList<>()).add(new long[] {logTime, chunk.length()});
            }
            RecordCodec.write(new Message(channelId, sequence, logTime, publishTime, data), chunk);
            if (chunk.length() > options.chunkSize()) {
                finishChunk();
            }
        } else {
            RecordCodec.write(new Message(channelId, sequence, logTime, publishTime, data), buffer);
            emit(true);
        }
    }

    /**
     * Adds an attachment (never inside a chunk).
     *
     * @throws IOException if the stream fails
     */
    public synchronized void addAttachment(long logTime, long createTime, String name, String mediaType, byte[] data) throws IOException {
        requireOpen();
        long offset = position + buffer.length();
        long length = RecordCodec.write(new Attachment(logTime, createTime, name, mediaType, data, 0), buffer);
        attachmentCount++;
        if (options.has(Feature.ATTACHMENT_INDEX)) {
            attachmentIndexes.add(new AttachmentIndex(offset, length, logTime, createTime, data.length, name, mediaType));
        }
        emit(true);
    }

    /**
     * Adds a metadata record.
     *
     * @throws IOException if the stream fails
     */
    public synchronized void addMetadata(String name, Map<String, String> metadata) throws IOException {
        requireOpen();
        long offset = position + buffer.length();
        long length = RecordCodec.write(new Metadata(name, metadata), buffer);
        metadataCount++;
        if (options.has(Feature.METADATA_INDEX)) {
            metadataIndexes.add(new MetadataIndex(offset, length, name));
        }
        emit(true);
    }

    /**
     * Writes the open chunk now, if it holds messages, and flushes the stream: a recording killed
     * later keeps everything up to here.
     *
     * @throws IOException if the stream fails
     */
    public synchronized void flushChunk() throws IOException {
        if (closed) {
            return;
        }
        finishChunk();
        out.flush();
    }

    private void finishChunk() throws IOException {
        if (!options.has(Feature.CHUNKED) || chunkMessages == 0) {
            return;
        }
        chunkCount++;
        byte[] records = chunk.toByteArray();
        CRC32 crc = new CRC32();
        crc.update(records);
        long chunkOffset = position + buffer.length();
        long chunkLength = RecordCodec.write(new Chunk(chunkStart, chunkEnd, records.length, (int) crc.getValue(), "", records), buffer);
        emit(true);
        Map<Integer, Long> indexOffsets = new LinkedHashMap<>();
        long indexStart = position;
        for (Map.Entry<Integer, List<long[]>> e : chunkMessageIndex.entrySet()) {
            long[] times = new long[e.getValue().size()];
            long[] offsets = new long[times.length];
            for (int i = 0; i < times.length; i++) {
                times[i] = e.getValue().get(i)[0];
                offsets[i] = e.getValue().get(i)[1];
            }
            indexOffsets.put(e.getKey(), position + buffer.length());
            RecordCodec.write(new MessageIndex(e.getKey(), times, offsets), buffer);
        }
        long indexLength = position + buffer.length() - indexStart;
        emit(true);
        if (options.has(Feature.CHUNK_INDEX)) {
            chunkIndexes.add(new ChunkIndex(chunkStart, chunkEnd, chunkOffset, chunkLength, indexOffsets, indexLength, "", records.length,
                    records.length));
        }
        chunk.reset();
        chunkMessageIndex.clear();
        chunkMessages = 0;
        chunkStart = 0;
        chunkEnd = 0;
    }

    /** Ends the data section, writes the summary and the footer, and closes the stream. */
    @Override
    public synchronized void close() throws IOException {
        if (closed) {
            return;
        }
        try {
            if (!started) {
                start("", "robomw");
            }
            finishChunk();
            RecordCodec.write(new DataEnd((int) dataCrc.getValue()), buffer);
            emit(false);
            closed = true;
            writeSummary();
            out.flush();
        } finally {
            closed = true;
            out.close();
        }
    }

    /**
     * Closes the stream without writing anything more: for a writer whose start failed, or that
     * is given up. What was written stays as it is (readable as far as it goes, with
     * {@link McapReader.Options#tolerant()}). Idempotent; {@link #close()} after it does nothing.
     *
     * @throws IOException if closing the stream fails
     */
    public synchronized void abandon() throws IOException {
        if (closed) {
            return;
        }
        closed = true;
        out.close();
    }

    private void writeSummary() throws IOException {
        CRC32 summaryCrc = new CRC32();
        long summaryStart = position;
        List<SummaryOffset> groups = new ArrayList<>();
        if (options.has(Feature.REPEAT_SCHEMAS)) {
            group(groups, Mcap.OP_SCHEMA, new ArrayList<>(schemas.values()), summaryCrc);
        }
        if (options.has(Feature.REPEAT_CHANNELS)) {
            group(groups, Mcap.OP_CHANNEL, new ArrayList<>(channels.values()), summaryCrc);
        }
        if (options.has(Feature.STATISTICS)) {
            group(groups, Mcap.OP_STATISTICS, List.of(new Statistics(messageCount, schemas.size(), channels.size(), attachmentCount, metadataCount,
                    chunkCount, messageStart, messageEnd, channelMessageCounts)), summaryCrc);
        }
        if (options.has(Feature.METADATA_INDEX)) {
            group(groups, Mcap.OP_METADATA_INDEX, new ArrayList<>(metadataIndexes), summaryCrc);
        }
        if (options.has(Feature.ATTACHMENT_INDEX)) {
            group(groups, Mcap.OP_ATTACHMENT_INDEX, new ArrayList<>(attachmentIndexes), summaryCrc);
        }
        if (options.has(Feature.CHUNK_INDEX)) {
            group(groups, Mcap.OP_CHUNK_INDEX, new ArrayList<>(chunkIndexes), summaryCrc);
        }
        long summaryOffsetStart = position;
        long summaryLength = summaryOffsetStart - summaryStart;
        if (options.has(Feature.SUMMARY_OFFSETS)) {
            for (SummaryOffset g : groups) {
                if (g.groupLength() != 0) {
                    RecordCodec.write(g, buffer);
                }
            }
        }
        long footerSummaryStart = summaryLength == 0 ? 0 : summaryStart;
        long footerOffsetStart = options.has(Feature.SUMMARY_OFFSETS) ? summaryOffsetStart : 0;
        RecordCodec.write(new Footer(footerSummaryStart, footerOffsetStart, 0), buffer);
        // The summary CRC runs from the summary's start through the footer's summary_offset_start field.
        summaryCrc.update(buffer.array(), 0, buffer.length() - 4);
        buffer.u32At(buffer.length() - 4, summaryCrc.getValue());
        buffer.raw(Mcap.MAGIC);
        emit(false);
    }

    private void group(List<SummaryOffset> groups, int opcode, List<McapRecord> records, CRC32 crc) throws IOException {
        long start = position;
        for (McapRecord r : records) {
            RecordCodec.write(r, buffer);
        }
        crc.update(buffer.array(), 0, buffer.length());
        emit(false);
        groups.add(new SummaryOffset(opcode, start, position - start));
    }

    private void requireOpen() {
        if (!started) {
            throw new IllegalStateException("start() the MCAP writer first");
        }
        if (closed) {
            throw new IllegalStateException("this MCAP writer is closed");
        }
    }

    /** Writes the buffer out, counting it into the data section's CRC when it belongs to it. */
    private void emit(boolean dataSection) throws IOException {
        if (dataSection) {
            dataCrc.update(buffer.array(), 0, buffer.length());
        }
        out.write(buffer.array(), 0, buffer.length());
        position += buffer.length();
        buffer.reset();
    }
}
