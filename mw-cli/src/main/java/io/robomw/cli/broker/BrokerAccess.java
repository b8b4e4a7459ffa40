package io.robomw.cli.broker;

import com.hivemq.embedded.EmbeddedExtension;
import com.hivemq.extension.sdk.api.ExtensionMain;
import com.hivemq.extension.sdk.api.auth.SimpleAuthenticator;
import com.hivemq.extension.sdk.api.auth.parameter.SimpleAuthInput;
import com.hivemq.extension.sdk.api.auth.parameter.SimpleAuthOutput;
import com.hivemq.extension.sdk.api.auth.parameter.TopicPermission;
import com.hivemq.extension.sdk.api.packets.auth.DefaultAuthorizationBehaviour;
import com.hivemq.extension.sdk.api.packets.auth.ModifiableDefaultPermissions;
import com.hivemq.extension.sdk.api.packets.connect.ConnackReasonCode;
import com.hivemq.extension.sdk.api.parameter.ExtensionStartInput;
import com.hivemq.extension.sdk.api.parameter.ExtensionStartOutput;
import com.hivemq.extension.sdk.api.parameter.ExtensionStopInput;
import com.hivemq.extension.sdk.api.parameter.ExtensionStopOutput;
import com.hivemq.extension.sdk.api.services.Services;
import com.hivemq.extension.sdk.api.services.builder.Builders;
import io.robomw.agents.messaging.mqtt.MqttTopics;
import io.robomw.agents.net.ThrottledWarnings;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.time.Duration;
import java.util.concurrent.atomic.LongAdder;

/**
 * Who may connect to {@code mw broker} and what they may do there, as a HiveMQ CE extension
 * embedded in the broker: only its user ({@link BrokerUser}); no anonymous client. The access
 * rules (ACL) for the {@code robomw/} tree: a client may publish a presence only under its own
 * client identifier ({@code robomw/presence/CLIENT-ID}, retained or not, which is also where its
 * will goes), so nobody can replace another node's presence; everything else is allowed to the
 * user. Refused connections are counted and logged (one line a second at most).
 */
final class BrokerAccess implements ExtensionMain {

    private static final Logger LOG = LoggerFactory.getLogger(BrokerAccess.class);

    private final BrokerUser user;
    private final MqttTopics topics = new MqttTopics(MqttTopics.DEFAULT_PREFIX);
    private final LongAdder refused = new LongAdder();
    private final ThrottledWarnings refusals = new ThrottledWarnings(LOG, Duration.ofSeconds(1));

    private BrokerAccess(BrokerUser user) {
        this.user = user;
    }

    /**
     * @param user the broker's user
     * @return the extension to embed in the broker
     */
    static EmbeddedExtension extension(BrokerUser user) {
        return EmbeddedExtension.builder().withId("robomw-access").withName("RoboMW broker access").withVersion("1")
                .withPriority(1000).withStartPriority(1000).withExtensionMain(new BrokerAccess(user)).build();
    }

    @Override
    public void extensionStart(ExtensionStartInput input, ExtensionStartOutput output) {
        SimpleAuthenticator authenticator = this::onConnect;
        Services.securityRegistry().setAuthenticatorProvider(providerInput -> authenticator);
    }

    @Override
    public void extensionStop(ExtensionStopInput input, ExtensionStopOutput output) {
        // nothing held
    }

    private void onConnect(SimpleAuthInput input, SimpleAuthOutput output) {
        String clientId = input.getClientInformation().getClientId();
        String name = input.getConnectPacket().getUserName().orElse(null);
        if (!user.admits(name, input.getConnectPacket().getPassword().orElse(null))) {
            refused.increment();
            refusals.warn("mw broker: refused client '{}' from {}: {} ({} refused so far)", clientId,
                    input.getConnectionInformation().getInetAddress().map(Object::toString).orElse("?"),
                    name == null ? "anonymous clients are not let in" : "wrong user name or password", refused.sum());
            output.failAuthentication(name == null ? ConnackReasonCode.NOT_AUTHORIZED : ConnackReasonCode.BAD_USER_NAME_OR_PASSWORD,
                    "this broker lets in its user only (mw broker prints where its credentials are)");
            return;
        }
        ModifiableDefaultPermissions p = output.getDefaultPermissions();
        String own = topics.presence(clientId);
        p.add(permission(own, TopicPermission.PermissionType.ALLOW, TopicPermission.MqttActivity.ALL));
        p.add(permission(topics.prefix() + "/presence/#", TopicPermission.PermissionType.DENY, TopicPermission.MqttActivity.PUBLISH));
        p.add(permission("#", TopicPermission.PermissionType.ALLOW, TopicPermission.MqttActivity.ALL));
        p.setDefaultBehaviour(DefaultAuthorizationBehaviour.DENY);
        output.authenticateSuccessfully();
    }

    private static TopicPermission permission(String filter, TopicPermission.PermissionType type, TopicPermission.MqttActivity activity) {
        return Builders.topicPermission().topicFilter(filter).type(type).activity(activity).build();
    }
}
