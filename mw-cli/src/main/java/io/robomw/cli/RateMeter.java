package io.robomw.cli;

import java.util.ArrayDeque;
import java.util.Locale;

/**
 * The rate of a topic's messages, as {@code ros2 topic hz} gives it: the mean rate over a window
 * of the latest intervals between arrivals, with their shortest, longest and standard deviation.
 * Thread-safe.
 */
final class RateMeter {

    private final int window;
    private final ArrayDeque<Long> intervals = new ArrayDeque<>();
    private long last = Long.MIN_VALUE;
    private long count;

    /** @param window how many of the latest intervals count */
    RateMeter(int window) {
        this.window = window;
    }

    /** @param nanos when a message arrived (System.nanoTime) */
    synchronized void arrived(long nanos) {
        count++;
        if (last != Long.MIN_VALUE) {
            intervals.addLast(nanos - last);
            if (intervals.size() > window) {
                intervals.removeFirst();
            }
        }
        last = nanos;
    }

    /** @return messages so far */
    synchronized long count() {
        return count;
    }

    /** @return one line: "rate 20.00 Hz: min 0.049 s, max 0.051 s, std dev 0.0004 s, window 19 (20 messages)", or why there is none yet */
    synchronized String line() {
        if (intervals.isEmpty()) {
            return "rate: " + (count == 0 ? "no messages yet" : "1 message so far, no interval yet");
        }
        double sum = 0;
        long min = Long.MAX_VALUE;
        long max = 0;
        for (long i : intervals) {
            sum += i;
            min = Math.min(min, i);
            max = Math.max(max, i);
        }
        double mean = sum / intervals.size();
        double var = 0;
        for (long i : intervals) {
            var += (i - mean) * (i - mean);
        }
        double std = Math.sqrt(var / intervals.size());
        return String.format(Locale.ROOT, "rate %.2f Hz: min %.3f s, max %.3f s, std dev %.4f s, window %d (%d messages)",
                1e9 / mean, min / 1e9, max / 1e9, std / 1e9, intervals.size(), count);
    }
}
