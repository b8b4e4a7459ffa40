package io.robomw.console.foxglove;

import java.net.URI;
import java.util.Set;

/**
 * Which clients may drive robots, by the {@code Origin} header of their handshake. A browser sends
 * the Origin of the page that opens a WebSocket, and lets any page open one to
 * {@code ws://127.0.0.1}; so RoboMW, like the Foxglove SDK, lets every client watch, but takes
 * Twists only from clients that send no Origin (programs that are not web pages: a Python script,
 * a bridge) or whose Origin is Foxglove's web app or a page served by this machine
 * ({@code localhost}, {@code 127.x}, {@code [::1]}). A client with another Origin (another web site
 * open in the same browser) can watch, never drive: its serverInfo does not offer clientPublish.
 */
final class Origins {

    /** Web origins trusted to drive besides this machine's own pages. */
    static final Set<String> TRUSTED = Set.of("https://app.foxglove.dev");

    private Origins() {
    }

    /**
     * @param origin the handshake's Origin header, or null
     * @return whether a client with that origin may publish (drive robots)
     */
    static boolean mayDrive(String origin) {
        if (origin == null || origin.isBlank()) {
            return true;
        }
        if (TRUSTED.contains(origin.trim().toLowerCase(java.util.Locale.ROOT))) {
            return true;
        }
        try {
            String host = URI.create(origin.trim()).getHost();
            return host != null && (host.equalsIgnoreCase("localhost") || host.equals("[::1]") || host.equals("::1") || host.startsWith("127."));
        } catch (IllegalArgumentException e) {
            return false;
        }
    }
}
