package io.robomw.config.robot;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.PlatformServices;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;
import org.junit.jupiter.api.Test;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertTrue;

class DescriptionRobotFactoryTest {

    @ParameterizedTest
    @ValueSource(strings = {"nxt", "ev3", "rcx", "ft-intelligent", "ft-txt", "aibo"})
    void shouldNameTheArtifactThatHasTheDriverOfEveryBrickPlatform(String platform) {
        String message = DescriptionRobotFactory.noDriver(platform, List.of("sim"));

        assertTrue(message.startsWith("no driver for platform '" + platform + "' on the class path (drivers on the class path: sim); add io.robomw:mw-platform"),
                message);
    }

    @Test
    void shouldSuggestAKnownPlatformForAMisspeltOne() {
        String message = DescriptionRobotFactory.noDriver("rcs", List.of());

        assertTrue(message.contains("unknown platform 'rcs'; did you mean 'rcx'?"), message);
    }

    @Test
    void shouldGiveTheProgramsFailurePolicyToTheRobotsOwnerThreads() {
        FailurePolicy programs = FailurePolicy.logging();

        assertSame(programs, DescriptionRobotFactory.failurePolicy(PlatformServices.none().with(FailurePolicy.class, programs)));
    }
}
