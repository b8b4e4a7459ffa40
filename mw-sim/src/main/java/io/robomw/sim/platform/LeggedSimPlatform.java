package io.robomw.sim.platform;

import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.command.HighLevelCommandPlatform;
import io.robomw.sim.SimRobot;
import io.robomw.sim.legged.Quadruped;
import io.robomw.sim.legged.UrbiKernel;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * The simulator's command platform for a legged robot. Walking commands act on the simulated
 * quadruped by their meaning, whatever the firmware's template says ({@code move} walks
 * {@code distance} at {@code speed}, {@code turn}, {@code arc}, {@code drive}), so a robot file
 * written for another firmware walks in the simulator too. Named actions are run by their text
 * through the dog's URBI server core, as the emulated Aibo runs them: their templates must be
 * URBI ({@code robot.sit()}, {@code headPan.val = 30 time:400}).
 *
 * <p>Runs on the thread that cycles the robot in the world, as the quadruped does; no I/O.
 */
final class LeggedSimPlatform extends HighLevelCommandPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(LeggedSimPlatform.class);

    private final Quadruped dog;
    private final UrbiKernel.Session session;
    private final Map<Run, Object> current = new ConcurrentHashMap<>();
    private final Map<String, Run> byTag = new ConcurrentHashMap<>();

    LeggedSimPlatform(PlatformConfig config, SimRobot robot) {
        super(config.robotName(), config.clock());
        this.dog = robot.quadruped();
        UrbiKernel kernel = robot.kernel();
        kernel.switchMotorsOn();
        this.session = kernel.open("platform", this::message);
    }

    @Override
    protected void start(Run run) {
        HighLevelCommand c = run.command();
        Quadruped.Motion m = switch (c.name()) {
            case "move" -> dog.walk(c.argument("distance"), c.argument("speed"));
            case "turn" -> dog.turn(c.argument("angle"), c.argument("speed"));
            case "arc" -> dog.arc(c.argument("radius"), c.argument("angle"), c.argument("speed"));
            case "drive" -> dog.drive(c.argument("linear"), c.argument("angular"));
            default -> null;
        };
        if (m != null) {
            current.put(run, m);
            m.onEnd(completed -> {
                if (current.get(run) != m) {
                    return;
                }
                if (completed) {
                    finished(run);
                } else {
                    failed(run, "the simulated dog ended '" + c.name() + "' before it was done");
                }
            });
            return;
        }
        String tag = "c" + run.id();
        current.put(run, tag);
        byTag.put(tag, run);
        session.submit(tag + "+end: { " + c.text() + " },\n");
    }

    @Override
    protected void refresh(Run run) {
        current.remove(run);
        start(run);
    }

    @Override
    protected void stop(Run run) {
        Object what = current.remove(run);
        if (what instanceof Quadruped.Motion m) {
            if (dog.current() == m) {
                dog.stop();
            }
        } else if (what instanceof String tag) {
            byTag.remove(tag);
            session.submit("stop " + tag + ",\n");
        }
    }

    private void message(long millis, String tag, UrbiKernel.Kind kind, String text) {
        Run run = byTag.get(tag);
        if (run == null) {
            if (kind == UrbiKernel.Kind.ERROR) {
                LOG.warn("robot '{}': the simulated dog reported: !!! {}", robot(), text);
            }
            return;
        }
        if (kind == UrbiKernel.Kind.ERROR) {
            failed(run, "the simulated dog answered \"!!! " + text + "\"");
        } else if (kind == UrbiKernel.Kind.SYSTEM && text.equals("end")) {
            byTag.remove(tag);
            current.remove(run, tag);
            finished(run);
        }
    }
}
