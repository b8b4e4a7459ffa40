package io.robomw.console.record;

import java.io.IOException;
import java.io.InputStream;
import java.io.UncheckedIOException;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;

/**
 * The JSON Schemas of the messages {@link RecordingCodec} makes, by name ({@code foxglove.PoseInFrame},
 * {@code robomw.SensorReading}, ...): the one source both a recording ({@link McapRecorder}, MCAP
 * schema records) and the live Foxglove WebSocket ({@code io.robomw.console.foxglove}, advertised
 * channels) take them from, so one Foxglove layout shows a live world and its recording. They are
 * files in this jar ({@code /io/robomw/console/schemas/NAME.json}); Foxglove's own come from the
 * foxglove-sdk repository (see the README beside them). All are read when this class is loaded;
 * immutable afterwards.
 */
public final class Schemas {

    /** How every message is encoded, in MCAP's and the Foxglove WebSocket's words. */
    public static final String MESSAGE_ENCODING = "json";
    /** How every schema is encoded. */
    public static final String SCHEMA_ENCODING = "jsonschema";

    private static final String FOLDER = "/io/robomw/console/schemas/";
    /** Every schema the codec uses. */
    private static final List<String> NAMES = List.of("robomw.WorldMap", "foxglove.SceneUpdate", "foxglove.PoseInFrame",
            "foxglove.FrameTransform", "robomw.SensorReading", "robomw.RobotCommand", "robomw.RobotStatus", "robomw.HostView",
            "robomw.AgentEvent", "foxglove.Log", "robomw.TopicMessage");
    private static final Map<String, byte[]> LOADED = load();

    private Schemas() {
    }

    /**
     * @param name a schema's name, as {@link RecordingCodec.Out#schema()} gives it
     * @return its JSON Schema (do not change the array: it is shared)
     * @throws IllegalStateException if this jar has no schema of that name (a codec bug, not bad input)
     */
    public static byte[] json(String name) {
        byte[] schema = LOADED.get(name);
        if (schema == null) {
            throw new IllegalStateException("no JSON schema " + name + " in the console's jar; it has " + LOADED.keySet());
        }
        return schema;
    }

    /** @return the names of every schema there is */
    public static Set<String> names() {
        return LOADED.keySet();
    }

    private static Map<String, byte[]> load() {
        Map<String, byte[]> m = new LinkedHashMap<>();
        for (String name : NAMES) {
            m.put(name, read(name));
        }
        return java.util.Collections.unmodifiableMap(m);
    }

    private static byte[] read(String name) {
        try (InputStream in = Schemas.class.getResourceAsStream(FOLDER + name + ".json")) {
            if (in == null) {
                throw new IllegalStateException("no JSON schema " + name + " in the console's jar (" + FOLDER + name + ".json)");
            }
            return in.readAllBytes();
        } catch (IOException e) {
            throw new UncheckedIOException("cannot read the JSON schema " + name + " from the console's jar", e);
        }
    }
}
