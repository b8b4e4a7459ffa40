package io.robomw.api.spi;

import io.robomw.api.UnsupportedActionException;
import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Components found once for many robots behave as those found robot by robot (mw-api's class path has no provider). */
class RobotComponentsTest {

    @Test
    void shouldGiveEveryRobotOfOneLookupAComponentOfItsOwnThatNamesItWhenNoProviderIsOnTheClassPath() {
        RobotComponents found = RobotComponents.find();
        MessagingComponent first = found.messagingOf("bot-1", MessagingConfig.defaults("bot-1", "bot.yaml"));
        MessagingComponent second = found.messagingOf("bot-2", MessagingConfig.defaults("bot-2", "bot.yaml"));
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> second.sendMessage("x", "host", "pass", "topic", "hello", "f"));
        assertEquals("bot-2", e.robot());
        assertTrue(e.getMessage().contains("mw-agents"), e::getMessage);
        assertEquals(0, first.addresses().size());
        AgencyComponent agency = found.agencyOf("bot-3", AgencyConfig.defaults("bot-3", "bot.yaml"));
        assertTrue(agency.homeAddress().isEmpty());
        assertTrue(agency.toString().contains("no agent runtime"), agency::toString);
        // the one-robot forms say the same
        UnsupportedActionException single = assertThrows(UnsupportedActionException.class,
                () -> RobotComponents.messaging("bot-4", MessagingConfig.defaults("bot-4", "bot.yaml")).sendMessage("x", "host", "pass", "topic", "hello", "f"));
        assertEquals("bot-4", single.robot());
    }
}
