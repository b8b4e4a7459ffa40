package io.robomw.console.record;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import io.robomw.console.observe.HostView;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.WorldMap;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeSet;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/** Every message the codec makes names a schema there is, and each schema is the JSON Schema of that name. */
class SchemasTest {

    @Test
    void everySchemaTheCodecUsesIsThereAndNoOther() throws Exception {
        WorldMap world = new WorldMap("arena", 4, 3, true, 0.1, 0.8, List.of(), List.of(), List.of());
        List<Observation> all = List.of(new Observation.World(1, world), new Observation.RobotPose(1, "r", 0, 0, 0, true),
                new Observation.SensorReading(1, "r", "s", 1, "m"), new Observation.RobotCommand(1, "r", "stop", Map.of()),
                new Observation.RobotStatus(1, "r", "", true, ""),
                new Observation.HostSeen(1, new HostView("rmi://127.0.0.1:1/h", "h", true, "r", List.of(), null, "", 1)),
                new Observation.AgentEvent(1, "a", "x.A", "report", "h", ""), new Observation.TopicMessage(1, "t", "x"));
        Set<String> used = new TreeSet<>();
        for (Observation o : all) {
            RecordingCodec.encode(o).forEach(m -> used.add(m.schema()));
        }
        assertEquals(used, new TreeSet<>(Schemas.names()));
        ObjectMapper json = new ObjectMapper();
        for (String name : used) {
            JsonNode schema = json.readTree(Schemas.json(name));
            assertEquals(name, schema.get("title").asText());
        }
    }

    @Test
    void anUnknownSchemaIsACodecBugNamedAsSuch() {
        assertThrows(IllegalStateException.class, () -> Schemas.json("foxglove.Nothing"));
    }
}
