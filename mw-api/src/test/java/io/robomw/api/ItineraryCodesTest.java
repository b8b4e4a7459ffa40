package io.robomw.api;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.EnumSource;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InvalidObjectException;
import java.io.ObjectInputStream;
import java.io.ObjectOutputStream;
import java.util.List;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The itinerary's serial form writes its enums as explicit codes and refuses codes it does not know. */
class ItineraryCodesTest {

    /** The codes as the serial form defines them (the ordinals they replaced). */
    private static final Map<Itinerary.UnreachablePolicy, Integer> POLICY_CODES = Map.of(
            Itinerary.UnreachablePolicy.SKIP, 0, Itinerary.UnreachablePolicy.RETRY, 1, Itinerary.UnreachablePolicy.RETURN_HOME, 2);
    private static final Map<Itinerary.Outcome, Integer> OUTCOME_CODES = Map.of(
            Itinerary.Outcome.DONE, 0, Itinerary.Outcome.FAILED, 1, Itinerary.Outcome.UNREACHABLE, 2, Itinerary.Outcome.INTERRUPTED, 3);
    /** current -1, round 0, rounds 3: the bytes just before the policy code. */
    private static final byte[] POSITION = {-1, -1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 3};

    @ParameterizedTest
    @EnumSource(Itinerary.UnreachablePolicy.class)
    void everyPolicyTravelsAsItsCodeAndComesBack(Itinerary.UnreachablePolicy policy) throws Exception {
        byte[] bytes = serialize(plan().onUnreachable(policy));
        assertEquals(POLICY_CODES.get(policy), (int) bytes[indexAfter(bytes, POSITION)], "the byte after the position is the policy's code");
        assertEquals(policy, read(bytes).unreachablePolicy());
        assertEquals(policy, Itinerary.UnreachablePolicy.fromCode(policy.code()));
    }

    @ParameterizedTest
    @EnumSource(Itinerary.Outcome.class)
    void everyOutcomeTravelsAsItsCodeAndComesBack(Itinerary.Outcome outcome) throws Exception {
        Itinerary it = plan();
        it.record("rmi://127.0.0.1:1099/a", outcome, "why");
        Itinerary back = read(serialize(it));
        assertEquals(List.of(new Itinerary.Visit(0, "rmi://127.0.0.1:1099/a", outcome, "why")), back.history());
        assertEquals((int) OUTCOME_CODES.get(outcome), outcome.code());
        assertEquals(outcome, Itinerary.Outcome.fromCode(outcome.code()));
    }

    @Test
    void anUnknownPolicyCodeIsRefusedNamingTheCode() throws Exception {
        byte[] bytes = serialize(plan());
        bytes[indexAfter(bytes, POSITION)] = 9;
        InvalidObjectException e = assertThrows(InvalidObjectException.class, () -> read(bytes));
        assertTrue(e.getMessage().contains("unknown unreachable-policy code 9"), e.getMessage());
    }

    @Test
    void anUnknownOutcomeCodeIsRefusedNamingTheCode() throws Exception {
        Itinerary it = plan();
        it.record("h", Itinerary.Outcome.INTERRUPTED, "d");
        byte[] bytes = serialize(it);
        // The visit: its round (int 0), its host (a String object "h": TC_STRING, length 1, 'h'), then
        // the outcome code, in a new block of primitive data (TC_BLOCKDATA, its length).
        byte[] visit = {0, 0, 0, 0, 0x74, 0, 1, 'h', 0x77};
        int at = indexAfter(bytes, visit) + 1;
        assertEquals(3, bytes[at]);
        bytes[at] = (byte) 200;
        InvalidObjectException e = assertThrows(InvalidObjectException.class, () -> read(bytes));
        assertTrue(e.getMessage().contains("unknown visit-outcome code 200"), e.getMessage());
    }

    private static Itinerary plan() {
        return new Itinerary().addStop("rmi://127.0.0.1:1099/a").repeat(3);
    }

    private static byte[] serialize(Itinerary it) throws IOException {
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        try (ObjectOutputStream out = new ObjectOutputStream(bytes)) {
            out.writeObject(it);
        }
        return bytes.toByteArray();
    }

    private static Itinerary read(byte[] bytes) throws IOException, ClassNotFoundException {
        try (ObjectInputStream in = new ObjectInputStream(new ByteArrayInputStream(bytes))) {
            return (Itinerary) in.readObject();
        }
    }

    private static int indexAfter(byte[] bytes, byte[] pattern) {
        for (int i = 0; i + pattern.length < bytes.length; i++) {
            boolean match = true;
            for (int j = 0; j < pattern.length && match; j++) {
                match = bytes[i + j] == pattern[j];
            }
            if (match) {
                return i + pattern.length;
            }
        }
        throw new AssertionError("pattern not found in the serial form");
    }
}
