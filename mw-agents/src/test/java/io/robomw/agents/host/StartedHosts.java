package io.robomw.agents.host;

import org.junit.jupiter.api.extension.AfterEachCallback;
import org.junit.jupiter.api.extension.ExtensionContext;

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
