package io.robomw.sim.emulator.mavlink;

import io.robomw.platform.mavlink.link.UdpMavlinkLink;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.MavResult;
import io.robomw.platform.mavlink.wire.MessageType;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.testkit.Await;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * A minimal ground station for the emulator's tests, on the codec and a real UDP socket: it
 * sends what a test asks and keeps every frame the vehicle sends. Sends as system 245, component
 * 190 (MAVSDK's ids).
 */
final class TestGroundStation implements AutoCloseable {

    static final Duration WAIT = Duration.ofSeconds(20);
    final UdpMavlinkLink link;
    final FrameEncoder encoder;
    final List<Frame> received = new CopyOnWriteArrayList<>();
    private final Map<MessageType, Payload> latest = new ConcurrentHashMap<>();
    private final Thread reader;
    private volatile boolean open = true;

    TestGroundStation(InetSocketAddress vehicle) throws IOException {
        this(vehicle, new FrameEncoder(245, 190));
    }

    TestGroundStation(InetSocketAddress vehicle, FrameEncoder encoder) throws IOException {
        this.link = UdpMavlinkLink.sendTo(vehicle, System::nanoTime);
        this.encoder = encoder;
        this.reader = new Thread(() -> {
            while (open) {
                try {
                    link.receive(Duration.ofMillis(100), (f, a) -> {
                        received.add(f);
                        latest.put(f.type().orElseThrow(), f.payload());
                    });
                } catch (IOException e) {
                    return;
                }
            }
        }, "test-gcs");
        reader.setDaemon(true);
        reader.start();
    }

    void send(Payload p) {
        try {
            link.send(encoder.encode(p));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    Payload awaitLatest(MessageType type) {
        Await.until(type.name() + " from the vehicle", WAIT, () -> latest.containsKey(type));
        return latest.get(type);
    }

    Payload latest(MessageType type) {
        return latest.get(type);
    }

    /** Sends a COMMAND_LONG (again every second, as a client retries) until its COMMAND_ACK comes. */
    MavResult command(MavCmd command, double... params) {
        double[] p = java.util.Arrays.copyOf(params, 7);
        if (params.length < 7) {
            java.util.Arrays.fill(p, params.length, 7, 0);
        }
        int before = received.size();
        Payload c = Payload.of(Messages.CommandLong.MESSAGE)
                .set(Messages.CommandLong.TARGET_SYSTEM, 1).set(Messages.CommandLong.TARGET_COMPONENT, 1)
                .set(Messages.CommandLong.COMMAND, command.code());
        Field7.fill(c, p);
        send(c);
        Payload[] ack = new Payload[1];
        Await.until("COMMAND_ACK of " + command, WAIT, () -> {
            List<Frame> now = List.copyOf(received); // a copy: the reader adds while this looks (a live subList would throw)
            for (Frame f : now.subList(before, now.size())) {
                if (f.is(Messages.CommandAck.MESSAGE) && f.payload().getLong(Messages.CommandAck.COMMAND) == command.code()) {
                    ack[0] = f.payload();
                    return true;
                }
            }
            return false;
        });
        if (ack[0].getLong(Messages.CommandAck.TARGET_SYSTEM) != 245 || ack[0].getLong(Messages.CommandAck.TARGET_COMPONENT) != 190) {
            throw new AssertionError("COMMAND_ACK not addressed to its sender: " + ack[0]);
        }
        return MavResult.of(ack[0].getLong(Messages.CommandAck.RESULT));
    }

    /** The seven params of COMMAND_LONG. */
    static final class Field7 {
        static void fill(Payload c, double[] p) {
            c.set(Messages.CommandLong.PARAM1, p[0]).set(Messages.CommandLong.PARAM2, p[1]).set(Messages.CommandLong.PARAM3, p[2])
                    .set(Messages.CommandLong.PARAM4, p[3]).set(Messages.CommandLong.PARAM5, p[4]).set(Messages.CommandLong.PARAM6, p[5])
                    .set(Messages.CommandLong.PARAM7, p[6]);
        }
    }

    @Override
    public void close() throws InterruptedException {
        open = false;
        reader.join(2000);
        link.close();
    }
}
