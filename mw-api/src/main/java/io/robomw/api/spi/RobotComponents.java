package io.robomw.api.spi;

import io.robomw.api.UnsupportedActionException;

import java.lang.reflect.InvocationHandler;
import java.lang.reflect.Proxy;
import java.util.List;
import java.util.Optional;
import java.util.ServiceLoader;

/**
 * Finds the providers that give every robot its communication component and its agency
 * ({@link MessagingProvider}, {@link AgencyProvider}, through {@link ServiceLoader}), so that the
 * Configuration Layer and the simulator link the paper's four components without compiling
 * against {@code mw-agents}. Without a provider on the class path a robot still moves and senses,
 * and its messaging or agency calls throw {@link UnsupportedActionException} saying which
 * artifact adds them.
 */
public final class RobotComponents {

    private static final String ADD_AGENTS = "add io.robomw:mw-agents to the class path (the mw distribution has it)";

    private final Optional<MessagingProvider> messagingProvider;
    private final Optional<AgencyProvider> agencyProvider;

    private RobotComponents(Optional<MessagingProvider> messagingProvider, Optional<AgencyProvider> agencyProvider) {
        this.messagingProvider = messagingProvider;
        this.agencyProvider = agencyProvider;
    }

    /**
     * Looks the providers up once, for a caller that opens many robots (a simulation of 100,000
     * robots scanned the class path twice a robot, which took minutes).
     *
     * @return the first messaging and agency providers on the class path, if any
     */
    public static RobotComponents find() {
        ClassLoader loader = RobotComponents.class.getClassLoader();
        return new RobotComponents(ServiceLoader.load(MessagingProvider.class, loader).findFirst(),
                ServiceLoader.load(AgencyProvider.class, loader).findFirst());
    }

    /**
     * @param robotName the robot, for error messages
     * @param config    its messaging settings
     * @return its communication component from the first provider found, or one that refuses every call
     */
    public static MessagingComponent messaging(String robotName, MessagingConfig config) {
        return new RobotComponents(ServiceLoader.load(MessagingProvider.class, RobotComponents.class.getClassLoader()).findFirst(),
                Optional.empty()).messagingOf(robotName, config);
    }

    /**
     * @param robotName the robot, for error messages
     * @param config    its agency settings
     * @return its agency from the first provider found, or one that refuses every call
     */
    public static AgencyComponent agency(String robotName, AgencyConfig config) {
        return new RobotComponents(Optional.empty(),
                ServiceLoader.load(AgencyProvider.class, RobotComponents.class.getClassLoader()).findFirst()).agencyOf(robotName, config);
    }

    /**
     * @param robotName the robot, for error messages
     * @param config    its messaging settings
     * @return its communication component from the provider {@link #find} found, or one that refuses every call
     */
    public MessagingComponent messagingOf(String robotName, MessagingConfig config) {
        return messagingProvider.map(p -> p.open(config))
                .orElseGet(() -> absent(MessagingComponent.class, robotName, "no messaging provider is on the class path; " + ADD_AGENTS));
    }

    /**
     * @param robotName the robot, for error messages
     * @param config    its agency settings
     * @return its agency from the provider {@link #find} found, or one that refuses every call
     */
    public AgencyComponent agencyOf(String robotName, AgencyConfig config) {
        return agencyProvider.map(p -> p.open(config))
                .orElseGet(() -> absent(AgencyComponent.class, robotName, "no agent runtime is on the class path; " + ADD_AGENTS));
    }

    /**
     * The component of a robot that has none: every call of the paper's operations throws
     * {@link UnsupportedActionException} naming the robot, the operation and why; it receives
     * nowhere, has no home, and closes without doing anything.
     */
    private static <T> T absent(Class<T> component, String robot, String why) {
        InvocationHandler refuse = (proxy, method, args) -> switch (method.getName()) {
            case "addresses" -> List.of();
            case "homeAddress" -> Optional.empty();
            case "close" -> null;
            case "toString" -> component.getSimpleName() + "[absent: " + why + "]";
            case "hashCode" -> System.identityHashCode(proxy);
            case "equals" -> proxy == args[0];
            default -> throw new UnsupportedActionException(robot, method.getName(), why);
        };
        return component.cast(Proxy.newProxyInstance(component.getClassLoader(), new Class<?>[]{component}, refuse));
    }
}
