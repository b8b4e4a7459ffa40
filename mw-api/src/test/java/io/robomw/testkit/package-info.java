/**
 * The test kit every module's tests share, shipped as {@code mw-api}'s test-jar: the one wait
 * with a deadline ({@link io.robomw.testkit.Await}, over Awaitility), the lines the tests' logger
 * printed ({@link io.robomw.testkit.LogLines}), busy threads that load the machine as a busy
 * laptop would ({@link io.robomw.testkit.BusyThreads}), loopback ports below the ephemeral range
 * ({@link io.robomw.testkit.Ports}) for a server restarted at its address, and the bytes a step
 * allocates ({@link io.robomw.testkit.Allocations}). Platform tests add {@code ScriptedLink}
 * (mw-platform's test-jar); agent tests add {@code StartedHosts} (mw-agents' test-jar).
 */
package io.robomw.testkit;
