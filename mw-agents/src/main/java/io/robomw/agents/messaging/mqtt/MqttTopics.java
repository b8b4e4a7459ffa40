package io.robomw.agents.messaging.mqtt;

import java.nio.charset.StandardCharsets;

/**
 * Where RoboMW puts things on a broker, all under one prefix (default {@value #DEFAULT_PREFIX}):
 *
 * <table>
 * <caption>MQTT topics</caption>
 * <tr><th>MQTT topic</th><th>what is published there</th></tr>
 * <tr><td>{@code PREFIX/pub/TOPIC}</td><td>publications on the RoboMW topic {@code TOPIC} ({@code publishMessage})</td></tr>
 * <tr><td>{@code PREFIX/msg/NAME}</td><td>messages to the receiver {@code NAME} ({@code sendMessage}), with an MQTT 5
 *     response topic and correlation data</td></tr>
 * <tr><td>{@code PREFIX/reply/CLIENT}</td><td>replies to the requests of the MQTT client {@code CLIENT} (its response topic)</td></tr>
 * <tr><td>{@code PREFIX/presence/CLIENT}</td><td>retained: what the client's node is and serves ({@link PresenceRecord}),
 *     replaced by its will when the client is gone</td></tr>
 * </table>
 *
 * <p>A RoboMW topic's {@code /} separate MQTT topic levels, so {@code robot/nxt-1} becomes
 * {@code robomw/pub/robot/nxt-1} and a plain MQTT client can subscribe to {@code robomw/pub/robot/#}.
 * The characters MQTT reserves in names ({@code +}, {@code #}, NUL) and {@code %} itself are written
 * as {@code %2B}, {@code %23}, {@code %00} and {@code %25}, so every RoboMW topic and name has exactly one MQTT topic.
 *
 * @param prefix the first levels of every topic, without a trailing {@code /}
 */
public record MqttTopics(String prefix) {

    /** The prefix when the address gives none. */
    public static final String DEFAULT_PREFIX = "robomw";

    /** Checks the prefix. */
    public MqttTopics {
        if (prefix.isEmpty() || prefix.startsWith("/") || prefix.endsWith("/") || prefix.startsWith("$")
                || prefix.indexOf('+') >= 0 || prefix.indexOf('#') >= 0 || prefix.indexOf('\0') >= 0) {
            throw new IllegalArgumentException("MQTT topic prefix '" + prefix + "' must be one or more topic levels (for example robomw or lab/robomw)"
                    + " without + # NUL, not starting with $ and without a leading or trailing /");
        }
    }

    /** @param topic a RoboMW topic @return the MQTT topic of its publications */
    public String publication(String topic) {
        return prefix + "/pub/" + escape(topic);
    }

    /** @param receiver a receiver name @return the MQTT topic of messages to it */
    public String request(String receiver) {
        return prefix + "/msg/" + escape(receiver);
    }

    /** @param clientId an MQTT client identifier @return the response topic of that client's requests */
    public String replies(String clientId) {
        return prefix + "/reply/" + escape(clientId);
    }

    /** @param clientId an MQTT client identifier @return where that client's presence is retained */
    public String presence(String clientId) {
        return prefix + "/presence/" + escape(clientId);
    }

    /** @return the filter that matches every presence */
    public String everyPresence() {
        return prefix + "/presence/+";
    }

    /** @return what every publication topic starts with */
    String publicationPrefix() {
        return prefix + "/pub/";
    }

    /** @return what every request topic starts with */
    String requestPrefix() {
        return prefix + "/msg/";
    }

    /** @return what every presence topic starts with */
    String presencePrefix() {
        return prefix + "/presence/";
    }

    /**
     * @param mqttTopic a publication's MQTT topic
     * @return its RoboMW topic, or {@code null} if it is not a publication under this prefix
     */
    public String topicOfPublication(String mqttTopic) {
        return mqttTopic.startsWith(publicationPrefix()) ? unescape(mqttTopic.substring(publicationPrefix().length())) : null;
    }

    /**
     * @param name a RoboMW topic or name
     * @return it, with {@code % + #} and NUL written as {@code %25 %2B %23 %00}
     */
    static String escape(String name) {
        StringBuilder b = null;
        for (int i = 0; i < name.length(); i++) {
            char c = name.charAt(i);
            String code = switch (c) {
                case '%' -> "%25";
                case '+' -> "%2B";
                case '#' -> "%23";
                case '\0' -> "%00";
                default -> null;
            };
            if (code != null && b == null) {
                b = new StringBuilder(name.length() + 8).append(name, 0, i);
            }
            if (b != null) {
                if (code != null) {
                    b.append(code);
                } else {
                    b.append(c);
                }
            }
        }
        return b == null ? name : b.toString();
    }

    /**
     * @param escaped an escaped name
     * @return the name
     * @throws IllegalArgumentException on a {@code %} not followed by two hex digits
     */
    static String unescape(String escaped) {
        if (escaped.indexOf('%') < 0) {
            return escaped;
        }
        byte[] utf8 = escaped.getBytes(StandardCharsets.UTF_8);
        java.io.ByteArrayOutputStream out = new java.io.ByteArrayOutputStream(utf8.length);
        for (int i = 0; i < utf8.length; i++) {
            if (utf8[i] == '%') {
                if (i + 2 >= utf8.length || Character.digit(utf8[i + 1], 16) < 0 || Character.digit(utf8[i + 2], 16) < 0) {
                    throw new IllegalArgumentException("'" + escaped + "': % must be followed by two hex digits");
                }
                out.write(Character.digit(utf8[i + 1], 16) * 16 + Character.digit(utf8[i + 2], 16));
                i += 2;
            } else {
                out.write(utf8[i]);
            }
        }
        return out.toString(StandardCharsets.UTF_8);
    }
}
