package io.robomw.it.messaging;

import org.junit.jupiter.api.Test;

import java.util.List;

/** TCP between this JVM and a peer JVM. */
class TcpMessagingIT extends PointToPointIT {

    @Override
    String bindAddress() {
        return "tcp://127.0.0.1:0";
    }

    @Test
    void tenThousandPublicationsArriveInOrder() {
        List<Object> got = subscribeToPeer("numbers");
        peer.ask("publish numbers 0 10000 -", "PUBLISHED");
        waitUntil(() -> got.size() >= 10_000);
        assertInOrder(got, 10_000);
    }
}
