package io.robomw.it.messaging;

import org.junit.jupiter.api.Test;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * UDP between this JVM and a peer JVM. UDP promises neither delivery nor order, so publications
 * go in batches of 100, each waited for; on loopback every one arrives, and the stream sequence
 * numbers show no loss.
 */
class UdpMessagingIT extends PointToPointIT {

    @Override
    String bindAddress() {
        return "udp://127.0.0.1:0";
    }

    @Test
    void pacedPublicationsAllArriveWithoutLoss() {
        List<Object> got = subscribeToPeer("numbers");
        for (int from = 0; from < 1000; from += 100) {
            peer.ask("publish numbers " + from + " 100 -", "PUBLISHED");
            int expected = from + 100;
            waitUntil(() -> got.size() >= expected);
        }
        assertInOrder(got, 1000);
        assertEquals(0, local.stats().framesLost());
    }
}
