package io.robomw.console.rosbridge.server;

import org.junit.jupiter.api.Test;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The token and the Origin decide who may connect. */
class HandshakeTest {

    private static final String TOKEN = "0123456789abcdef-token";

    @Test
    void withoutATokenProgramsAndThisMachinesPagesMayConnect() {
        Handshake h = new Handshake(null, List.of());
        assertTrue(h.check("/", null, null, null).accepted(), "roslibpy sends no Origin");
        assertTrue(h.check("/", null, null, "http://localhost:8000").accepted());
        assertTrue(h.check("/", null, null, "http://127.0.0.1:5173").accepted());
        assertTrue(h.check("/", null, null, "http://[::1]:3000").accepted());
    }

    @Test
    void anotherSitesPageIsRefusedUnlessItsOriginIsAllowed() {
        Handshake h = new Handshake(null, List.of("https://dash.example.org"));
        Handshake.Verdict v = h.check("/", null, null, "https://evil.example.com");
        assertEquals(403, v.status());
        assertTrue(v.reason().contains("--allow-origin https://evil.example.com"), v.reason());
        assertTrue(h.check("/", null, null, "https://dash.example.org").accepted());
        assertEquals(403, h.check("/", null, null, "null").status(), "a sandboxed or file page");
        assertEquals(403, h.check("/", null, null, "http://localhost.evil.com").status());
        assertTrue(new Handshake(null, List.of("*")).check("/", null, null, "https://any.example").accepted());
    }

    @Test
    void aTokenIsTakenInTheQueryThePathOrTheAuthorizationHeader() {
        Handshake h = new Handshake(TOKEN, List.of());
        assertTrue(h.check("/", "token=" + TOKEN, null, null).accepted());
        assertTrue(h.check("/", "x=1&token=" + TOKEN, null, null).accepted());
        assertTrue(h.check("/" + TOKEN, null, null, null).accepted());
        assertTrue(h.check("/", null, "Bearer " + TOKEN, null).accepted());
        assertTrue(h.check("/", "token=" + TOKEN, null, "https://anywhere.example").accepted(), "a page with the token may connect from anywhere");
    }

    @Test
    void aMissingOrWrongTokenIsRefusedWith401() {
        Handshake h = new Handshake(TOKEN, List.of());
        assertEquals(401, h.check("/", null, null, null).status());
        assertEquals(401, h.check("/", "token=wrong", null, null).status());
        assertEquals(401, h.check("/wrong", null, "Bearer wrong", null).status());
        assertEquals(401, h.check("/", "token=" + TOKEN.substring(1), null, null).status());
    }
}
