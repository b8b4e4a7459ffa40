package io.robomw.console.rosbridge.server;

import org.eclipse.jetty.websocket.api.Callback;
import org.eclipse.jetty.websocket.api.Session;

/**
 * A plain WebSocket echo on the bridge's own server (its {@code echo} path, off unless asked
 * for): the baseline a rosbridge round trip is measured against (bench/rosbridge).
 */
public final class EchoSocket extends Session.Listener.AbstractAutoDemanding {

    @Override
    public void onWebSocketText(String text) {
        Session s = getSession();
        if (s != null && s.isOpen()) {
            s.sendText(text, Callback.NOOP);
        }
    }
}
