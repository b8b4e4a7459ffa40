package io.robomw.bench;

import org.junit.jupiter.api.Test;

/**
 * Runs {@link MqttBenchmark} under failsafe when the {@code bench} profile names it
 * ({@code -Dit.test=MqttBenchmarkRun}, as {@code bench/mqtt} does); the normal test run does not
 * include this class (it does not end in IT).
 */
class MqttBenchmarkRun {

    @Test
    void run() throws Exception {
        MqttBenchmark.main(new String[0]);
    }
}
