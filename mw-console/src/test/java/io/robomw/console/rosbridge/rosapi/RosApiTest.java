package io.robomw.console.rosbridge.rosapi;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.msg.Interfaces;
import io.robomw.console.rosbridge.msg.Wire;
import org.junit.jupiter.api.Test;

import java.time.Clock;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** rosapi's services answer what clients ask first, in rosapi's shapes. */
class RosApiTest {

    private final Graph graph = new Graph(Interfaces.load());

    RosApiTest() {
        RosApi.offer(graph, Clock.systemUTC());
        graph.declare("/nxt/odom", graph.interfaces().message("nav_msgs/Odometry"), false).addPublisher("/nxt");
    }

    private JsonNode call(String service, String field, String value) throws Exception {
        ObjectNode req = JsonNodeFactory.instance.objectNode();
        if (field != null) {
            req.put(field, value);
        }
        var s = graph.service(service).orElseThrow();
        ObjectNode full = new io.robomw.console.rosbridge.msg.MessageReader(graph.interfaces(), Clock.systemUTC()).read(req, s.type().request());
        return s.handler().call(full).get(5, TimeUnit.SECONDS);
    }

    @Test
    void topicsAreListedWithTheirTypesInROS2sSpelling() throws Exception {
        JsonNode r = call("/rosapi/topics", null, null);
        assertEquals("[\"/nxt/odom\"]", Wire.json(r.get("topics")));
        assertEquals("[\"nav_msgs/msg/Odometry\"]", Wire.json(r.get("types")));
        assertEquals("nav_msgs/msg/Odometry", call("/rosapi/topic_type", "topic", "/nxt/odom").get("type").asText());
        assertEquals("", call("/rosapi/topic_type", "topic", "/nowhere").get("type").asText(), "rosapi answers an unknown topic with an empty type");
        assertEquals("[\"/nxt/odom\"]", Wire.json(call("/rosapi/topics_for_type", "type", "nav_msgs/Odometry").get("topics")));
        assertEquals("[\"/nxt\"]", Wire.json(call("/rosapi/publishers", "topic", "/nxt/odom").get("publishers")));
    }

    @Test
    void servicesAndNodesAreListed() throws Exception {
        assertTrue(call("/rosapi/services", null, null).get("services").toString().contains("/rosapi/topics"));
        assertEquals("rosapi_msgs/srv/Topics", call("/rosapi/service_type", "service", "/rosapi/topics").get("type").asText());
        assertEquals("/rosapi", call("/rosapi/service_node", "service", "/rosapi/topics").get("node").asText());
        assertEquals("[\"/nxt\",\"/rosapi\",\"/rosbridge_websocket\"]", Wire.json(call("/rosapi/nodes", null, null).get("nodes")));
        assertEquals("[\"/nxt/odom\"]", Wire.json(call("/rosapi/node_details", "node", "/nxt").get("publishing")));
    }

    @Test
    void messageDetailsAreRosapisTypeDefs() throws Exception {
        JsonNode defs = call("/rosapi/message_details", "type", "geometry_msgs/msg/PoseWithCovariance").get("typedefs");
        assertEquals("{\"type\":\"geometry_msgs/PoseWithCovariance\",\"fieldnames\":[\"pose\",\"covariance\"],\"fieldtypes\":[\"geometry_msgs/Pose\",\"double\"],"
                + "\"fieldarraylen\":[-1,36],\"examples\":[\"{}\",\"[]\"],\"constnames\":[],\"constvalues\":[]}", Wire.json(defs.get(0)));
        assertEquals("geometry_msgs/Quaternion", defs.get(3).get("type").asText());
        assertEquals("1.0", defs.get(3).get("examples").get(3).asText(), "w defaults to 1");
        JsonNode request = call("/rosapi/service_request_details", "type", "robomw_msgs/srv/Move").get("typedefs");
        assertEquals("robomw_msgs/Move_Request", request.get(0).get("type").asText());
        assertEquals("[\"double\",\"double\"]", Wire.json(request.get(0).get("fieldtypes")));
    }

    @Test
    void itIsROS2Jazzy() throws Exception {
        JsonNode v = call("/rosapi/get_ros_version", null, null);
        assertEquals(2, v.get("version").intValue());
        assertEquals("jazzy", v.get("distro").asText());
        assertTrue(call("/rosapi/get_time", null, null).at("/time/sec").longValue() > 1_700_000_000L);
    }
}
