package io.robomw.console.rosbridge;

import com.fasterxml.jackson.databind.JsonNode;
import io.robomw.console.rosbridge.protocol.Limits;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A simulated copter of the harbour world over the endpoint: its battery sensor is a
 * {@code sensor_msgs/msg/BatteryState} topic, as ROS 2 drivers of flight controllers publish it
 * (mavros's {@code battery}, PX4's {@code battery_status} bridged), with what RoboMW measures filled in.
 */
class RosBridgeVehicleTest {

    private static final Duration WITHIN = Duration.ofSeconds(30);
    private static final Path HARBOUR = Path.of("../examples/worlds/harbour.yaml");

    @Test
    void aVehiclesBatteryIsABatteryStateTopicWithItsChargeAsAFractionAndUnmeasuredFieldsNull() throws Exception {
        try (Simulation sim = Simulation.load(HARBOUR)) {
            sim.startRealTime(1.0);
            try (RosBridge bridge = RosBridge.builder().listen("127.0.0.1", 0).rates(new Rates(10, 0)).limits(Limits.DEFAULTS.withMaxConnections(2))
                    .robot(BridgedRobot.simulated(sim.robot("copter"), sim.world().robot("copter"))).start();
                 WsClient c = WsClient.connect(bridge.address())) {
                c.send("{'op':'call_service','id':'tt','service':'/rosapi/topic_type','args':{'topic':'/copter/battery_state'}}");
                JsonNode type = c.await(f -> f.path("id").asText().equals("tt"), WITHIN, "the topic's type");
                assertEquals("sensor_msgs/msg/BatteryState", type.at("/values/type").asText(), type.toString());

                c.send("{'op':'subscribe','id':'b','topic':'/copter/battery_state'}");
                JsonNode battery = c.awaitPublish("/copter/battery_state", WITHIN);
                double fraction = battery.at("/msg/percentage").doubleValue();
                assertTrue(fraction > 0 && fraction <= 1, "the charge left, 0 to 1 as the message wants it: " + battery);
                assertEquals(sim.robot("copter").getValue("battery", io.robomw.api.ReturnType.PERCENT) / 100, fraction, 0.05, "what getValue reads");
                assertTrue(battery.at("/msg/present").booleanValue());
                assertTrue(battery.at("/msg/voltage").isNull(), "not measured: NaN, null on JSON: " + battery);
                assertEquals("battery", battery.at("/msg/location").asText());
                assertEquals("copter/base_link", battery.at("/msg/header/frame_id").asText());
            }
        }
    }
}
