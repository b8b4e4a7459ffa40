package io.robomw.examples.driver;

import io.robomw.platform.link.PseudoTerminal;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * A LineBot board, as its firmware would behave, on the master side of a pseudo-terminal: the
 * driver opens the slave as its serial port. Each motor turns at its commanded speed in real time
 * and counts its degrees; a braked motor stops at once; the board stops both motors when it hears
 * nothing for {@value LineBotProtocol#WATCHDOG_MILLIS} ms; it answers what it cannot do with the
 * protocol's {@code ERR} codes. Every request it took is kept, in order, for the test to check.
 */
final class LineBotEmulator implements AutoCloseable {

    private final PseudoTerminal pty;
    private final OutputStream out;
    private final Thread thread;
    private final List<String> requests = new CopyOnWriteArrayList<>();
    private final Map<Integer, Integer> inputs = new ConcurrentHashMap<>();
    private volatile boolean running = true;
    // Guarded by this:
    private final double[] speed = new double[2];
    private final double[] degrees = new double[2];
    private long lastUpdate = System.nanoTime();
    private long lastRequest = System.nanoTime();

    private LineBotEmulator(PseudoTerminal pty) {
        this.pty = pty;
        this.out = pty.masterOutput();
        this.thread = new Thread(this::serve, "linebot-emulator " + pty.devicePath());
        thread.setDaemon(true);
    }

    /**
     * @param pty the pseudo-terminal whose master it serves
     * @return the running board
     */
    static LineBotEmulator serve(PseudoTerminal pty) {
        LineBotEmulator board = new LineBotEmulator(pty);
        board.thread.start();
        return board;
    }

    /**
     * @param input 1 or 2
     * @param value what a READ of it answers from now on
     */
    void input(int input, int value) {
        inputs.put(input, value);
    }

    /** @return the requests taken so far, in order */
    List<String> requests() {
        return requests;
    }

    /** @return motor {@code A} or {@code B}'s true rotation, degrees since the last ZERO */
    synchronized double degrees(String motor) {
        advance(System.nanoTime());
        return degrees[motor.equals("A") ? 0 : 1];
    }

    private void serve() {
        byte[] buf = new byte[256];
        ByteArrayOutputStream line = new ByteArrayOutputStream();
        try {
            while (running) {
                int n = pty.read(buf, 0, buf.length, Duration.ofMillis(100));
                for (int i = 0; i < n; i++) {
                    if (buf[i] == LineBotProtocol.LF) {
                        String request = line.toString(StandardCharsets.US_ASCII);
                        line.reset();
                        requests.add(request);
                        out.write((answer(request) + "\n").getBytes(StandardCharsets.US_ASCII));
                        out.flush();
                    } else {
                        line.write(buf[i]);
                    }
                }
                synchronized (this) {
                    advance(System.nanoTime());
                }
            }
        } catch (IOException e) {
            // the pseudo-terminal closed: the board is switched off
        }
    }

    private synchronized String answer(String request) {
        long now = System.nanoTime();
        advance(now);
        lastRequest = now;
        String[] f = request.split(" ");
        return switch (f[0]) {
            case "HELLO" -> "LINEBOT " + LineBotProtocol.VERSION;
            case "ZERO" -> {
                degrees[0] = 0;
                degrees[1] = 0;
                yield "OK";
            }
            case "COUNT" -> "COUNT " + Math.round(degrees[0]) + " " + Math.round(degrees[1]);
            case "SPEED" -> {
                int m = motor(f);
                if (m < 0) {
                    yield "ERR 3 no such motor";
                }
                if (f.length != 3 || !f[2].matches("-?\\d+") || Math.abs(Integer.parseInt(f[2])) > LineBotProtocol.MAX_DEGREES_PER_SECOND) {
                    yield "ERR 2 speed must be -1000..1000";
                }
                speed[m] = Integer.parseInt(f[2]);
                yield "OK";
            }
            case "STOP" -> {
                int m = motor(f);
                if (m < 0) {
                    yield "ERR 3 no such motor";
                }
                if (f.length != 3 || !(f[2].equals("BRAKE") || f[2].equals("COAST"))) {
                    yield "ERR 2 stop with BRAKE or COAST";
                }
                speed[m] = 0; // a braked motor stops at once; a coasting one, as far as the board counts, too
                yield "OK";
            }
            case "READ" -> {
                Integer value = f.length == 2 ? inputs.get(f[1].equals("1") ? 1 : f[1].equals("2") ? 2 : -1) : null;
                yield value == null ? "ERR 3 no sensor on input " + (f.length == 2 ? f[1] : "?") : "VALUE " + f[1] + " " + value;
            }
            default -> "ERR 1 unknown command " + f[0];
        };
    }

    private static int motor(String[] f) {
        return f.length < 2 ? -1 : f[1].equals("A") ? 0 : f[1].equals("B") ? 1 : -1;
    }

    /** Turns the motors on to {@code now}, stopping them where the watchdog would have. */
    private void advance(long now) {
        long watchdog = lastRequest + LineBotProtocol.WATCHDOG_MILLIS * 1_000_000L;
        long until = Math.min(now, Math.max(lastUpdate, watchdog));
        for (int m = 0; m < 2; m++) {
            degrees[m] += speed[m] * (until - lastUpdate) / 1e9;
        }
        if (now > watchdog) {
            speed[0] = 0;
            speed[1] = 0;
        }
        lastUpdate = now;
    }

    /** Switches the board off: its thread ends within its read's timeout. */
    @Override
    public void close() throws InterruptedException {
        running = false;
        thread.join(10_000);
    }
}
