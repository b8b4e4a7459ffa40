package io.robomw.config.description;

import com.code_intelligence.jazzer.junit.FuzzTest;

import java.nio.charset.StandardCharsets;

/**
 * Fuzz test of the robot file loader (docs/fuzzing.md): any bytes as a robot YAML file. The only
 * refusal allowed is a {@link DescriptionException} naming the file (with line and column); a
 * description it returns must be whole.
 */
class RobotFileFuzzTest {

    private static final RobotDescriptionLoader LOADER = new RobotDescriptionLoader();

    @FuzzTest
    void robotFile(byte[] input) {
        RobotDescription d;
        try {
            d = LOADER.parse(new String(input, StandardCharsets.UTF_8), "fuzz.yaml");
        } catch (DescriptionException refused) {
            if (!refused.getMessage().contains("fuzz.yaml")) {
                throw new AssertionError("a refused robot file is not named: " + refused.getMessage(), refused);
            }
            return;
        }
        if (d.name() == null || d.platform() == null) {
            throw new AssertionError("a description without a name or platform was returned: " + d);
        }
    }
}
