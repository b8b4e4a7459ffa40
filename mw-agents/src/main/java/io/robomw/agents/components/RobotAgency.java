package io.robomw.agents.components;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.ClusterKeyLookup;
import io.robomw.api.Agent;
import io.robomw.api.AgentException;
import io.robomw.api.AgentRef;
import io.robomw.api.spi.AgencyComponent;
import io.robomw.api.spi.AgencyConfig;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.List;
import java.util.Optional;

/**
 * A robot's agency: agents sent from the robot ({@code robot.sendAgent(host, agent)}) get an
 * in-process home, a small {@link AgentHost} without a robot, where their reports and results
 * arrive and from which they can be retracted. The home starts on first use, with the cluster
 * key found by {@link ClusterKeyLookup} (the robot file's {@code agency.key_file}/{@code key_env},
 * then {@value AgencyConfig#KEY_VARIABLE}, then {@code ~/.robomw/cluster.key}); the start is
 * logged once. Closing the robot closes the home: agents still travelling then finish without
 * a home to report to.
 *
 * <p>Thread-safe.
 */
public final class RobotAgency implements AgencyComponent {

    private static final Logger LOG = LoggerFactory.getLogger(RobotAgency.class);

    private final AgencyConfig config;
    private final ClusterKeyLookup keys;
    private final Object lock = new Object();
    private volatile AgentHost home;
    private boolean closed;

    /**
     * @param config the robot's agency settings
     * @param keys   where the cluster key is looked for
     */
    public RobotAgency(AgencyConfig config, ClusterKeyLookup keys) {
        this.config = config;
        this.keys = keys;
    }

    /**
     * @param firstUse what the robot was asked to do, for the log line of the start
     * @return the home, started
     * @throws AgentException if it cannot start (no cluster key, the port in use)
     */
    public AgentHost home(String firstUse) {
        AgentHost h = home;
        if (h != null) {
            return h;
        }
        synchronized (lock) {
            if (closed) {
                throw new AgentException("the agency of " + config.source() + " is closed");
            }
            if (home == null) {
                try {
                    ClusterKey key = keys.require(config.clusterKey(), "the agency of " + config.source());
                    home = AgentHost.builder(config.homeName()).bind(config.bind()).port(config.port()).clusterKey(key)
                            .noMessaging().memoryStore().start();
                } catch (IOException | IllegalStateException e) {
                    throw new AgentException("cannot start the agents' home of " + config.source() + ": " + e.getMessage(), e);
                }
                LOG.info("agents' home '{}' ({}) started at {} on first use ({})", config.homeName(), config.source(), home.address(), firstUse);
            }
            return home;
        }
    }

    @Override
    public Optional<String> homeAddress() {
        AgentHost h = home;
        return h == null ? Optional.empty() : Optional.of(h.address());
    }

    @Override
    public AgentRef sendAgent(String host, Agent agent) {
        return home("sendAgent").agency().sendAgent(host, agent);
    }

    @Override
    public AgentRef startTrip(Agent agent) {
        return home("startTrip").agency().startTrip(agent);
    }

    @Override
    public List<AgentRef> dispatchClones(Agent agent, String... hosts) {
        return home("dispatchClones").agency().dispatchClones(agent, hosts);
    }

    @Override
    public void close() {
        AgentHost h;
        synchronized (lock) {
            closed = true;
            h = home;
        }
        if (h != null) {
            h.close();
        }
    }

    @Override
    public String toString() {
        return "agency of " + config.source();
    }
}
