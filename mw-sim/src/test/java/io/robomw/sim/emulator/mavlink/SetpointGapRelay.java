package io.robomw.sim.emulator.mavlink;

import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameDecoder;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.Messages;

import java.io.IOException;
import java.net.DatagramPacket;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.SocketAddress;
import java.net.SocketTimeoutException;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * A UDP relay on loopback between a ground station and a vehicle that holds back the ground
 * station's setpoints (SET_POSITION_TARGET_LOCAL_NED) until its first DO_SET_MODE has gone
 * through: to PX4 the stream has not begun when OFFBOARD is first asked for, as when a busy
 * machine stalls the ground station's sender. One datagram carries one frame (as the driver sends).
 */
final class SetpointGapRelay implements AutoCloseable {

    private final DatagramSocket socket;
    private final InetSocketAddress vehicle;
    private final Thread thread;
    private volatile boolean closed;
    private volatile SocketAddress groundStation;
    private volatile boolean modeAsked;
    private final AtomicInteger setModes = new AtomicInteger();
    private final AtomicInteger held = new AtomicInteger();

    SetpointGapRelay(InetSocketAddress vehicle) throws IOException {
        this.vehicle = vehicle;
        this.socket = new DatagramSocket(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
        socket.setSoTimeout(200);
        this.thread = new Thread(this::relay, "setpoint-gap-relay");
        thread.setDaemon(true);
        thread.start();
    }

    /** @return where the ground station sends */
    InetSocketAddress address() {
        return new InetSocketAddress(InetAddress.getLoopbackAddress(), socket.getLocalPort());
    }

    /** @return DO_SET_MODE commands the ground station sent (each retry of one counted) */
    int setModes() {
        return setModes.get();
    }

    /** @return setpoints held back */
    int held() {
        return held.get();
    }

    private void relay() {
        byte[] buf = new byte[2048];
        Frame[] last = new Frame[1];
        FrameDecoder decoder = new FrameDecoder(f -> last[0] = f);
        while (!closed) {
            DatagramPacket p = new DatagramPacket(buf, buf.length);
            try {
                socket.receive(p);
                if (p.getSocketAddress().equals(vehicle)) {
                    SocketAddress to = groundStation;
                    if (to != null) {
                        socket.send(new DatagramPacket(p.getData(), p.getOffset(), p.getLength(), to));
                    }
                    continue;
                }
                groundStation = p.getSocketAddress();
                last[0] = null;
                decoder.feedDatagram(p.getData(), p.getOffset(), p.getLength());
                Frame f = last[0];
                if (f != null && f.is(Messages.SetPositionTargetLocalNed.MESSAGE) && !modeAsked) {
                    held.incrementAndGet();
                    continue;
                }
                socket.send(new DatagramPacket(p.getData(), p.getOffset(), p.getLength(), vehicle));
                if (f != null && f.is(Messages.CommandLong.MESSAGE) && f.payload().getLong(Messages.CommandLong.COMMAND) == MavCmd.DO_SET_MODE.code()) {
                    setModes.incrementAndGet();
                    modeAsked = true;
                }
            } catch (SocketTimeoutException e) {
                // look at closed again
            } catch (IOException e) {
                if (!closed) {
                    throw new java.io.UncheckedIOException(e);
                }
            }
        }
    }

    @Override
    public void close() throws InterruptedException {
        closed = true;
        socket.close();
        thread.join(5_000);
    }
}
