package io.robomw.platform.mavlink.wire;

import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.math.BigInteger;
import java.nio.charset.StandardCharsets;
import java.time.Instant;
import java.time.InstantSource;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.List;
import java.util.Objects;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Frames pymavlink 2.4.50 made ({@code pymavlink-vectors.txt}, written by {@code make_vectors.py}
 * beside it: every field of 22 messages set, each also with its last fields zero so it is cut, and
 * four signed with MAVProxy's key from a passphrase): each decodes to the fields pymavlink was
 * given, and the codec encodes those fields to the same bytes, signature included.
 */
class PymavlinkVectorsTest {

    /** One line of the vectors file. */
    record Vector(String name, byte[] frame, int systemId, int componentId, int sequence, String signing, String fields) {
        @Override
        public String toString() {
            return name;
        }
    }

    static List<Vector> vectors() throws IOException {
        List<Vector> out = new ArrayList<>();
        try (BufferedReader r = new BufferedReader(new InputStreamReader(Objects.requireNonNull(
                PymavlinkVectorsTest.class.getResourceAsStream("pymavlink-vectors.txt")), StandardCharsets.UTF_8))) {
            for (String line; (line = r.readLine()) != null; ) {
                String[] p = line.split("\\|", -1);
                String[] ids = p[2].split("/");
                out.add(new Vector(p[0], HexFormat.of().parseHex(p[1]), Integer.parseInt(ids[0]), Integer.parseInt(ids[1]),
                        Integer.parseInt(ids[2]), p[3], p[4]));
            }
        }
        return out;
    }

    private static Frame decodeOne(byte[] bytes) {
        List<Frame> frames = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(frames::add);
        d.feed(bytes);
        assertEquals(1, frames.size(), "frames decoded");
        assertEquals(0, d.counts().badChecksums());
        return frames.get(0);
    }

    @ParameterizedTest
    @MethodSource("vectors")
    void decodesToTheFieldsPymavlinkWasGiven(Vector v) {
        Frame f = decodeOne(v.frame());
        assertTrue(f.type().isPresent(), "known message");
        assertEquals(v.systemId(), f.systemId());
        assertEquals(v.componentId(), f.componentId());
        assertEquals(v.sequence(), f.sequence());
        Payload p = f.payload();
        for (String assignment : v.fields().split(";")) {
            int eq = assignment.indexOf('=');
            Field field = p.type().field(assignment.substring(0, eq));
            String value = assignment.substring(eq + 1);
            if (field.type() == FieldType.CHAR) {
                assertEquals(value, p.getText(field), field.toString());
                continue;
            }
            String[] elements = field.arrayLength() > 0 ? value.split(",") : new String[]{value};
            for (int i = 0; i < elements.length; i++) {
                assertElement(p, field, i, elements[i]);
            }
        }
    }

    private static void assertElement(Payload p, Field field, int i, String expected) {
        switch (field.type()) {
            case FLOAT -> assertEquals((float) Double.parseDouble(expected), (float) p.getDouble(field, i), field + "[" + i + "]");
            case DOUBLE -> assertEquals(Double.parseDouble(expected), p.getDouble(field, i), field + "[" + i + "]");
            case UINT64_T -> assertEquals(new BigInteger(expected).longValue(), p.getLong(field, i), field + "[" + i + "]");
            default -> assertEquals(Long.parseLong(expected), p.getLong(field, i), field + "[" + i + "]");
        }
    }

    @ParameterizedTest
    @MethodSource("vectors")
    void encodesTheSameFieldsToTheSameBytes(Vector v) {
        Frame f = decodeOne(v.frame());
        FrameEncoder e = new FrameEncoder(v.systemId(), v.componentId());
        for (int i = 0; i < v.sequence(); i++) {
            e.encode(Payload.of(Messages.Heartbeat.MESSAGE));
        }
        if (!v.signing().equals("-")) {
            String[] s = v.signing().split("@");
            e.signWith(new Signer(SigningKey.fromPassphrase(s[0]), Integer.parseInt(s[1]), InstantSource.fixed(Instant.EPOCH))
                    .startingAt(Long.parseLong(s[2])));
        }
        assertArrayEquals(v.frame(), e.encode(f.payload()), v.name());
    }

    @ParameterizedTest
    @MethodSource("vectors")
    void signedVectorsPassTheCheckWithThePassphraseAndFailWithAnother(Vector v) {
        if (v.signing().equals("-")) {
            return;
        }
        String phrase = v.signing().split("@")[0];
        Frame f = decodeOne(v.frame());
        InstantSource then = InstantSource.fixed(Instant.ofEpochSecond(SigningTime.EPOCH_UNIX_SECONDS));
        assertEquals(SignatureCheck.Verdict.ACCEPTED, new SignatureCheck(SigningKey.fromPassphrase(phrase), then).check(f));
        assertEquals(SignatureCheck.Verdict.WRONG_SIGNATURE, new SignatureCheck(SigningKey.fromPassphrase(phrase + "!"), then).check(f));
    }
}
