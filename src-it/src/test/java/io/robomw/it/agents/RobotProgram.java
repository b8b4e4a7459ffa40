package io.robomw.it.agents;

import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.examples.agents.SquareSurveyAgent;

import java.io.BufferedReader;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.util.concurrent.TimeUnit;

/**
 * A plain program against {@link Robot}, in its own JVM: {@code open FILE} ({@code Robots.open})
 * or {@code remote ADDRESS} ({@code Robots.remote}), then commands on stdin, one answer line each:
 * <ul>
 *   <li>{@code move METRES} moves the robot ({@code MOVED});</li>
 *   <li>{@code publish TOPIC PASSWORD TEXT} publishes with that password, or with {@code -} with the
 *       one the robot file names for the topic ({@code PUBLISHED});</li>
 *   <li>{@code send-agent HOST} sends a {@link SquareSurveyAgent} (from the examples jar, which the
 *       hosts lack) through the robot's agency and waits for its result ({@code RESULT ...});</li>
 *   <li>{@code exit}.</li>
 * </ul>
 * Failures answer {@code ERR ...}.
 */
public final class RobotProgram {

    private RobotProgram() {
    }

    public static void main(String[] args) throws Exception {
        try (Robot robot = args[0].equals("open") ? Robots.open(Path.of(args[1])) : Robots.remote(args[1])) {
            System.out.println("READY " + robot.name());
            BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
            for (String line; (line = in.readLine()) != null; ) {
                String[] w = line.strip().split(" ", 4);
                try {
                    switch (w[0]) {
                        case "move" -> {
                            robot.move(Double.parseDouble(w[1]), 0.2);
                            System.out.println("MOVED");
                        }
                        case "publish" -> {
                            robot.publishMessage(w[1], w[3], "tell", w[2].equals("-") ? null : w[2]);
                            System.out.println("PUBLISHED");
                        }
                        case "send-agent" -> {
                            Object result = robot.sendAgent(w[1], new SquareSurveyAgent(0.2)).result().get(120, TimeUnit.SECONDS);
                            System.out.println("RESULT " + result.toString().replace('\n', ' '));
                        }
                        case "exit" -> {
                            return;
                        }
                        default -> System.out.println("ERR unknown command " + w[0]);
                    }
                } catch (Exception e) {
                    System.out.println("ERR " + e.toString().replace('\n', ' '));
                }
            }
        }
    }
}
