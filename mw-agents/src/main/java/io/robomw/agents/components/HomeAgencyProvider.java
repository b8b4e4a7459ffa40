package io.robomw.agents.components;

import io.robomw.agents.host.ClusterKeyLookup;
import io.robomw.api.spi.AgencyComponent;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.AgencyProvider;

/** Gives every robot a {@link RobotAgency} with an in-process home; found through {@link java.util.ServiceLoader}. */
public final class HomeAgencyProvider implements AgencyProvider {

    @Override
    public AgencyComponent open(AgencyConfig config) {
        return new RobotAgency(config, ClusterKeyLookup.ofThisProcess());
    }
}
