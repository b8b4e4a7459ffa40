package io.robomw.agents.host;

import io.robomw.api.Agency;
import io.robomw.api.AgentContext;
import io.robomw.api.AgentRef;
import io.robomw.api.Itinerary;
import io.robomw.api.Messaging;
import io.robomw.api.Robot;

import java.io.Serializable;
import java.util.UUID;

/** An agent's view of the host it is at. */
final class HostContext implements AgentContext {

    private final AgentHost host;
    private final HostedAgent hosted;

    HostContext(AgentHost host, HostedAgent hosted) {
        this.host = host;
        this.hosted = hosted;
    }

    @Override
    public UUID agentId() {
        return hosted.id;
    }

    @Override
    public String hostName() {
        return host.name();
    }

    @Override
    public String hostAddress() {
        return host.address();
    }

    @Override
    public String homeAddress() {
        return hosted.home;
    }

    @Override
    public Robot robot() {
        Robot r = host.claimRobot(hosted);
        if (r == null) {
            throw new NoRobotException(host.name(), host.address());
        }
        return r;
    }

    @Override
    public Messaging messaging() {
        return host.messagingFor(hosted);
    }

    @Override
    public Itinerary itinerary() {
        return hosted.agent.itinerary();
    }

    @Override
    public void dispatch(String host) {
        // a host's name works as messages do (hosts that met, or met at a broker): resolved here, now
        hosted.agent.itinerary().insertNext(this.host.hostAddressOf(host, hosted), null);
    }

    @Override
    public AgentRef cloneAgent(Itinerary itinerary) {
        return host.cloneOf(hosted, itinerary);
    }

    @Override
    public boolean leaving() {
        return hosted.retractRequested || hosted.disposeRequested || Thread.currentThread().isInterrupted();
    }

    @Override
    public void dispose() {
        hosted.disposeRequested = true;
    }

    @Override
    public void setResult(Serializable result) {
        hosted.result = result;
    }

    @Override
    public void report(Serializable value) {
        host.report(hosted, value);
    }

    @Override
    public Agency agency() {
        return host.agency();
    }
}
