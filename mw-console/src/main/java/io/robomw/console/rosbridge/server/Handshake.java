package io.robomw.console.rosbridge.server;

import java.net.InetAddress;
import java.net.URI;
import java.net.URLDecoder;
import java.net.UnknownHostException;
import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.util.List;
import java.util.Locale;

/**
 * Who may open a rosbridge connection: checks the access token and the browser's Origin before
 * the WebSocket is accepted.
 *
 * <h2>Token</h2>
 * A bridge started with a token takes a connection only if it carries it, in any of three ways
 * (compared in constant time):
 * <ul>
 *   <li>a query parameter: {@code ws://HOST:9090/?token=TOKEN} (roslibpy:
 *   {@code Ros("ws://HOST:9090/?token=TOKEN")}; roslibjs: {@code new ROSLIB.Ros({url: ...})});</li>
 *   <li>the path: {@code ws://HOST:9090/TOKEN};</li>
 *   <li>a header: {@code Authorization: Bearer TOKEN} (roslibpy's {@code headers=}).</li>
 * </ul>
 * rosbridge_suite's ROS 2 server has no authentication at all (its {@code auth} op was removed),
 * so the token is RoboMW's extension; without one the bridge may only listen on loopback.
 *
 * <h2>Origin</h2>
 * A WebSocket is not bound by the browser's same-origin rule, so any web page a user opens could
 * otherwise drive the robots of a bridge on the user's machine. A handshake with an
 * {@code Origin} header (browsers always send one; roslibpy and other programs send none) is
 * taken only from a page on this machine ({@code http://localhost:*}, {@code http://127.0.0.1:*},
 * {@code http://[::1]:*}), from an origin given with {@code --allow-origin}, or with the token.
 */
final class Handshake {

    private final String token;
    private final List<String> allowedOrigins;

    /**
     * @param token          the access token, or {@code null} for none
     * @param allowedOrigins origins besides this machine's pages that browsers may connect from
     *                       ({@code https://dashboard.example.org}, or {@code *} for any)
     */
    Handshake(String token, List<String> allowedOrigins) {
        this.token = token;
        this.allowedOrigins = List.copyOf(allowedOrigins);
    }

    /** The verdict on a handshake. */
    record Verdict(int status, String reason) {
        static final Verdict ACCEPT = new Verdict(0, null);

        boolean accepted() {
            return status == 0;
        }
    }

    /**
     * @param path          the request's path
     * @param query         its query, or {@code null}
     * @param authorization its {@code Authorization} header, or {@code null}
     * @param origin        its {@code Origin} header, or {@code null}
     * @return accept, or the HTTP status and the reason to refuse with
     */
    Verdict check(String path, String query, String authorization, String origin) {
        boolean tokenGiven = token != null && presented(path, query, authorization);
        if (token != null && !tokenGiven) {
            return new Verdict(401, "this rosbridge needs its access token: ws://HOST:PORT/?token=TOKEN (docs/ros2.md)");
        }
        if (origin != null && !tokenGiven && !originAllowed(origin)) {
            return new Verdict(403, "web pages from " + origin + " may not use this rosbridge (start it with --allow-origin " + origin
                    + ", or give the page the access token)");
        }
        return Verdict.ACCEPT;
    }

    private boolean presented(String path, String query, String authorization) {
        if (authorization != null && authorization.regionMatches(true, 0, "Bearer ", 0, 7) && same(authorization.substring(7).trim())) {
            return true;
        }
        if (path != null && path.length() > 1 && same(decode(path.substring(1)))) {
            return true;
        }
        if (query != null) {
            for (String pair : query.split("&")) {
                int eq = pair.indexOf('=');
                if (eq > 0 && pair.substring(0, eq).equals("token") && same(decode(pair.substring(eq + 1)))) {
                    return true;
                }
            }
        }
        return false;
    }

    private boolean same(String given) {
        return MessageDigest.isEqual(given.getBytes(StandardCharsets.UTF_8), token.getBytes(StandardCharsets.UTF_8));
    }

    private boolean originAllowed(String origin) {
        if (allowedOrigins.contains("*") || allowedOrigins.stream().anyMatch(o -> o.equalsIgnoreCase(origin))) {
            return true;
        }
        try {
            URI o = URI.create(origin);
            String scheme = o.getScheme() == null ? "" : o.getScheme().toLowerCase(Locale.ROOT);
            if (!scheme.equals("http") && !scheme.equals("https") || o.getHost() == null) {
                return false;
            }
            String host = o.getHost().startsWith("[") ? o.getHost().substring(1, o.getHost().length() - 1) : o.getHost();
            if (host.equalsIgnoreCase("localhost")) {
                return true;
            }
            if (!host.matches("[0-9.]+|[0-9a-fA-F:]+")) {
                return false; // a name other than localhost: never looked up here
            }
            return InetAddress.getByName(host).isLoopbackAddress();
        } catch (IllegalArgumentException | UnknownHostException e) {
            return false;
        }
    }

    private static String decode(String s) {
        try {
            return URLDecoder.decode(s, StandardCharsets.UTF_8);
        } catch (IllegalArgumentException e) {
            return s;
        }
    }
}
