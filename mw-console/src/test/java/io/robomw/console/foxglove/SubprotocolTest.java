package io.robomw.console.foxglove;

import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.Optional;

import static org.junit.jupiter.api.Assertions.assertEquals;

/** Which subprotocol a handshake gets: the one offered, the SDK's name first, none when neither is offered. */
class SubprotocolTest {

    @Test
    void theSdkNameIsChosenWhenOffered() {
        assertEquals(Optional.of(Subprotocol.SDK_V1), Subprotocol.choose(List.of("foxglove.sdk.v1")));
    }

    @Test
    void theLegacyNameIsChosenWhenOnlyItIsOffered() {
        assertEquals(Optional.of(Subprotocol.WEBSOCKET_V1), Subprotocol.choose(List.of("foxglove.websocket.v1")));
    }

    @Test
    void theSdkNameWinsWhenBothAreOfferedInEitherOrder() {
        assertEquals(Optional.of(Subprotocol.SDK_V1), Subprotocol.choose(List.of("foxglove.websocket.v1", "foxglove.sdk.v1")));
        assertEquals(Optional.of(Subprotocol.SDK_V1), Subprotocol.choose(List.of("foxglove.websocket.v1, foxglove.sdk.v1")));
    }

    @Test
    void neitherOfferedChoosesNone() {
        assertEquals(Optional.empty(), Subprotocol.choose(List.of()));
        assertEquals(Optional.empty(), Subprotocol.choose(List.of("chat", "foxglove.sdk.v2")));
        assertEquals(Optional.empty(), Subprotocol.choose(List.of("FOXGLOVE.SDK.V1")));
    }
}
