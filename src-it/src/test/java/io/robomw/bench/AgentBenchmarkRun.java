package io.robomw.bench;

import org.junit.jupiter.api.Test;

/**
 * Runs {@link AgentBenchmark} under failsafe when asked for ({@code bench/agents}, that is
 * {@code -Pbench -Dit.test=AgentBenchmarkRun}); the normal test run does not include this class
 * (it does not end in IT).
 */
class AgentBenchmarkRun {

    @Test
    void run() throws Exception {
        // Host A logs like host B: warnings only (an info line per archive received would be timed too).
        System.setProperty("org.slf4j.simpleLogger.defaultLogLevel", "warn");
        AgentBenchmark.main(new String[0]);
    }
}
