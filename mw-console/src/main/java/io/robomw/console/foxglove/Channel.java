package io.robomw.console.foxglove;

/**
 * A channel the server advertises: one topic of the recordings' ({@code RecordingCodec}), with
 * its schema.
 *
 * @param id         the server's id for it (u32; ids are never reused while the server runs)
 * @param topic      its topic, {@code /robots/nxt/pose}
 * @param schemaName its schema's name, {@code foxglove.PoseInFrame}
 * @param schema     its JSON Schema, as text
 */
public record Channel(long id, String topic, String schemaName, String schema) {
}
