package io.robomw.console.foxglove;

import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.nio.charset.StandardCharsets;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A published Twist: forwards and turning only, finite numbers. */
class TwistTest {

    private static Twist parse(String json) throws IOException {
        return Twist.parse(json.getBytes(StandardCharsets.UTF_8));
    }

    @Test
    void aTeleopPanelsTwistDrivesForwardsAndTurns() throws Exception {
        assertEquals(new Twist(0.2, 0.5), parse("{\"linear\":{\"x\":0.2,\"y\":0,\"z\":0},\"angular\":{\"x\":0,\"y\":0,\"z\":0.5}}"));
    }

    @Test
    void missingComponentsAreZero() throws Exception {
        assertEquals(new Twist(0, -1), parse("{\"linear\":{},\"angular\":{\"z\":-1}}"));
    }

    @Test
    void sidewaysOrRollingCannotBeDriven() {
        IOException e = assertThrows(IOException.class, () -> parse("{\"linear\":{\"x\":0.1,\"y\":0.3},\"angular\":{}}"));
        assertTrue(e.getMessage().contains("linear.y = 0.3 cannot be driven"), e.getMessage());
    }

    @Test
    void notATwistIsRefused() {
        assertTrue(assertThrows(IOException.class, () -> parse("{\"linear\":{\"x\":\"fast\"},\"angular\":{}}")).getMessage()
                .contains("linear.x must be a finite number, got \"fast\""));
        assertTrue(assertThrows(IOException.class, () -> parse("{\"angular\":{}}")).getMessage().contains("needs an object \"linear\""));
        assertTrue(assertThrows(IOException.class, () -> parse("[]")).getMessage().contains("a Twist is a JSON object"));
        assertTrue(assertThrows(IOException.class, () -> parse("{nope")).getMessage().startsWith("a Twist must be JSON"));
        assertTrue(assertThrows(IOException.class, () -> parse("{\"linear\":{\"x\":1e999},\"angular\":{}}")).getMessage().contains("finite"));
    }
}
