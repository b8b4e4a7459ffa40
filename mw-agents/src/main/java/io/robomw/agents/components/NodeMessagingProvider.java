package io.robomw.agents.components;

import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.api.spi.MessagingComponent;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.api.spi.MessagingProvider;

/** Gives every robot a {@link RobotMessaging} with the default node settings; found through {@link java.util.ServiceLoader}. */
public final class NodeMessagingProvider implements MessagingProvider {

    @Override
    public MessagingComponent open(MessagingConfig config) {
        return new RobotMessaging(config, MessagingSettings.defaults(), System::getenv);
    }
}
