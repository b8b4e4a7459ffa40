/**
 * The {@code mqtt://} and {@code mqtts://} transports: RoboMW messaging through an MQTT 5 broker
 * (Mosquitto, HiveMQ, EMQX, {@code mw broker}), for robots and programs that cannot reach each
 * other directly. Frames travel whole as MQTT payloads under a topic prefix ({@link
 * io.robomw.agents.messaging.mqtt.MqttTopics}); requests use MQTT 5 request/response; nodes
 * announce themselves with retained presence and a will ({@link
 * io.robomw.agents.messaging.mqtt.BrokerDirectory} reads them). The client is the HiveMQ MQTT
 * client.
 */
package io.robomw.agents.messaging.mqtt;
