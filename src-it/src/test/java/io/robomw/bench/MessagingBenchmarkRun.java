package io.robomw.bench;

import org.junit.jupiter.api.Test;

/**
 * Runs {@link MessagingBenchmark} under failsafe when the {@code bench} profile asks for it; the
 * normal test run does not include this class (it does not end in IT).
 */
class MessagingBenchmarkRun {

    @Test
    void run() throws Exception {
        MessagingBenchmark.main(new String[0]);
    }
}
