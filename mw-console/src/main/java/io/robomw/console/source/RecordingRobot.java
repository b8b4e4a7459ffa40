package io.robomw.console.source;

import io.robomw.api.Robot;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;

import java.lang.reflect.InvocationHandler;
import java.lang.reflect.InvocationTargetException;
import java.lang.reflect.Method;
import java.lang.reflect.Proxy;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * A robot that tells an observer every command given to it, as it is given, and then does it:
 * {@code move}, {@code turn}, {@code arc}, {@code drive}, {@code stop}, {@code changeAltitude},
 * {@code perform} (blocking or not). Everything else passes straight through. What the robot does
 * and throws is unchanged.
 */
public final class RecordingRobot {

    /** Argument names of each verb, SI units (perform's arguments are numbered). */
    private static final Map<String, List<String>> VERBS = Map.of(
            "move", List.of("distance", "speed"),
            "turn", List.of("radians", "speed"),
            "arc", List.of("radius", "angle", "speed"),
            "drive", List.of("linearSpeed", "angularSpeed"),
            "stop", List.of(),
            "changeAltitude", List.of("metres", "speed"),
            "perform", List.of());

    private RecordingRobot() {
    }

    /**
     * @param robot    the robot
     * @param observer told each command
     * @return the same robot, recording its commands
     */
    public static Robot wrap(Robot robot, Observer observer) {
        InvocationHandler h = new InvocationHandler() {
            @Override
            public Object invoke(Object proxy, Method m, Object[] args) throws Throwable {
                String verb = m.getName().endsWith("Async") ? m.getName().substring(0, m.getName().length() - 5) : m.getName();
                List<String> names = VERBS.get(verb);
                if (names != null && m.getDeclaringClass() != Object.class) {
                    Map<String, Double> values = new LinkedHashMap<>();
                    String what = verb;
                    Object[] a = args == null ? new Object[0] : args;
                    for (int i = 0; i < a.length; i++) {
                        if (a[i] instanceof Double d && i < names.size()) {
                            values.put(names.get(i), d);
                        } else if (a[i] instanceof String s) {
                            what = verb + " " + s;
                        } else if (a[i] instanceof double[] ds) {
                            for (int j = 0; j < ds.length; j++) {
                                values.put("arg" + j, ds[j]);
                            }
                        }
                    }
                    observer.observe(new Observation.RobotCommand(System.currentTimeMillis() * 1_000_000L, robot.name(), what, values));
                }
                if (m.getName().equals("toString") && m.getParameterCount() == 0) {
                    return "RecordingRobot[" + robot + "]";
                }
                try {
                    return m.invoke(robot, args);
                } catch (InvocationTargetException e) {
                    throw e.getCause();
                }
            }
        };
        return (Robot) Proxy.newProxyInstance(Robot.class.getClassLoader(), new Class<?>[] {Robot.class}, h);
    }
}
