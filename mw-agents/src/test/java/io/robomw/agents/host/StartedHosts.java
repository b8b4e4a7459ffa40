package io.robomw.agents.host;

import io.robomw.testkit.Await;
import org.junit.jupiter.api.extension.AfterEachCallback;
import org.junit.jupiter.api.extension.ExtensionContext;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.BindException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

/**
 * The agent hosts a test starts, each closed after the test whatever it did (register as a
 * field with {@code @RegisterExtension}). A host that fails to close does not keep the others
 * open: every host is closed, then the first failure is thrown. In mw-agents' test-jar, for the
 * tests of every module that starts hosts.
 */
public final class StartedHosts implements AfterEachCallback {

    private final List<AgentHost> hosts = new ArrayList<>();

    /**
     * @param builder a host's builder
     * @return the host it started, closed after the test
     * @throws Exception if the host did not start
     */
    public AgentHost start(AgentHostBuilder builder) throws Exception {
        return add(builder.start());
    }

    /**
     * Starts a host again at the port its builder names, the port a closed host had (a restart):
     * the closed host's listening socket may take a moment to be released by RMI, so a start that
     * finds the port in use is tried again, up to 30 s. Give the first host a port from
     * {@link io.robomw.testkit.Ports#free()}: a port from the ephemeral range can be taken by
     * another process's outgoing connection in between, for good.
     *
     * @param builder the restarted host's builder, with its port
     * @return the host it started, closed after the test
     * @throws IOException if the host did not start for another reason than the port in use
     */
    public AgentHost restart(AgentHostBuilder builder) throws IOException {
        AgentHost[] started = new AgentHost[1];
        IOException[] inUse = new IOException[1];
        Await.until("the host starts again on its port", Duration.ofSeconds(30), () -> {
            try {
                started[0] = builder.start();
                return true;
            } catch (IOException e) {
                if (!portInUse(e)) {
                    throw new UncheckedIOException(e);
                }
                inUse[0] = e;
                return false;
            }
        }, () -> "; last: " + inUse[0]);
        return add(started[0]);
    }

    private static boolean portInUse(Throwable e) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            if (t instanceof BindException) {
                return true;
            }
        }
        return false;
    }

    /**
     * @param host a host the test started itself
     * @return the same host, now closed after the test
     */
    public AgentHost add(AgentHost host) {
        hosts.add(host);
        return host;
    }

    @Override
    public void afterEach(ExtensionContext context) {
        RuntimeException first = null;
        for (AgentHost h : hosts) {
            try {
                h.close();
            } catch (RuntimeException e) {
                if (first == null) {
                    first = e;
                } else {
                    first.addSuppressed(e);
                }
            }
        }
        hosts.clear();
        if (first != null) {
            throw first;
        }
    }
}
