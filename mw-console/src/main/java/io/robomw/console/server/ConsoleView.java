package io.robomw.console.server;

import io.robomw.console.observe.HostView;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import io.robomw.console.observe.WorldMap;

import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * What the console shows, kept up to date by observations: the world's map, every robot's pose,
 * trail and recent sensor values, every host with its agents, and the latest agent events. The
 * page is sent a full view when it connects and, about ten times a second, what changed since
 * (new trail points and events, the hosts and robots as they are). Thread-safe: observations come
 * from the sources' threads, views are made on the pusher's.
 *
 * <p>Staleness is explicit: a host that did not answer keeps the agents it last listed, marked
 * down with its error and the time it last answered; a robot that did not answer keeps its last
 * pose, marked unreachable. The page greys both and says how old they are.
 */
public final class ConsoleView implements Observer {

    /** Trail points kept per robot (older ones are thinned, never the newest). */
    static final int MAX_TRAIL = 20_000;
    /** A new trail point only when the robot moved at least this far, metres. */
    static final double TRAIL_STEP_METRES = 0.005;
    /** Sensor values kept per sensor for the little plots. */
    static final int SENSOR_HISTORY = 120;
    /** Events kept for pages that connect later. */
    static final int MAX_EVENTS = 500;

    private final Object lock = new Object();
    private final String title;
    private WorldMap world;
    private final Map<String, RobotState> robots = new LinkedHashMap<>();
    private final Map<String, HostView> hosts = new LinkedHashMap<>();
    private final Deque<Map<String, Object>> events = new ArrayDeque<>();
    private long eventSeq;
    private long worldVersion;
    private volatile long version;

    /** @param title shown at the top of the page (the command that runs the console) */
    public ConsoleView(String title) {
        this.title = title;
    }

    private static final class RobotState {
        final String name;
        double x;
        double y;
        double heading;
        double z;
        boolean hasPose;
        boolean truth;
        long poseNanos;
        boolean reachable = true;
        String source = "";
        String detail = "";
        String lastCommand = "";
        long commandNanos;
        final List<double[]> trail = new ArrayList<>();
        long trailDropped;
        final Map<String, SensorState> sensors = new LinkedHashMap<>();

        RobotState(String name) {
            this.name = name;
        }
    }

    private static final class SensorState {
        String unit = "";
        final Deque<double[]> values = new ArrayDeque<>();
    }

    @Override
    public void observe(Observation o) {
        synchronized (lock) {
            apply(o);
            version++;
        }
    }

    private void apply(Observation o) {
        if (o instanceof Observation.Batch b) {
            b.all().forEach(this::apply);
        } else if (o instanceof Observation.World w) {
            world = w.map();
            worldVersion++;
        } else if (o instanceof Observation.RobotPose raw) {
            Observation.RobotPose p = placed(raw);
            RobotState r = robot(p.robot());
            if (r.truth && !p.truth()) {
                return; // the simulator's truth wins over the robot's own estimate
            }
            r.truth = p.truth();
            r.x = p.x();
            r.y = p.y();
            r.heading = p.heading();
            r.z = p.z();
            r.poseNanos = p.timeNanos();
            boolean moved = r.trail.isEmpty() || Math.hypot(p.x() - r.trail.get(r.trail.size() - 1)[1], p.y() - r.trail.get(r.trail.size() - 1)[2])
                    >= TRAIL_STEP_METRES;
            if (moved || !r.hasPose) {
                r.trail.add(new double[] {p.timeNanos() / 1e9, p.x(), p.y()});
                if (r.trail.size() > MAX_TRAIL) {
                    r.trail.subList(0, MAX_TRAIL / 2).clear();
                    r.trailDropped += MAX_TRAIL / 2;
                }
            }
            r.hasPose = true;
        } else if (o instanceof Observation.SensorReading s) {
            SensorState st = robot(s.robot()).sensors.computeIfAbsent(s.sensor(), k -> new SensorState());
            st.unit = s.unit();
            st.values.addLast(new double[] {s.timeNanos() / 1e9, s.value()});
            while (st.values.size() > SENSOR_HISTORY) {
                st.values.removeFirst();
            }
        } else if (o instanceof Observation.RobotCommand c) {
            RobotState r = robot(c.robot());
            StringBuilder text = new StringBuilder(c.verb());
            c.args().forEach((k, v) -> text.append(' ').append(k).append('=').append(String.format(java.util.Locale.ROOT, "%.3g", v)));
            r.lastCommand = text.toString();
            r.commandNanos = c.timeNanos();
        } else if (o instanceof Observation.RobotStatus s) {
            RobotState r = robot(s.robot());
            r.reachable = s.reachable();
            r.source = s.source();
            r.detail = s.detail();
        } else if (o instanceof Observation.HostSeen h) {
            hosts.put(h.host().address(), h.host());
        } else if (o instanceof Observation.AgentEvent e) {
            Map<String, Object> m = new LinkedHashMap<>();
            m.put("seq", ++eventSeq);
            m.put("t", e.timeNanos() / 1e9);
            m.put("kind", "agent");
            m.put("agent", e.agent());
            m.put("agentClass", e.agentClass());
            m.put("what", e.kind());
            m.put("host", e.host());
            m.put("detail", e.detail());
            addEvent(m);
        } else if (o instanceof Observation.TopicMessage t) {
            Map<String, Object> m = new LinkedHashMap<>();
            m.put("seq", ++eventSeq);
            m.put("t", t.timeNanos() / 1e9);
            m.put("kind", "topic");
            m.put("topic", t.topic());
            m.put("detail", t.text());
            addEvent(m);
        }
    }

    /** A pose as the page draws it: odometry placed from the robot's start on the world's map ({@link WorldMap#placed}). */
    private Observation.RobotPose placed(Observation.RobotPose p) {
        return world == null ? p : world.placed(p);
    }

    private void addEvent(Map<String, Object> m) {
        events.addLast(m);
        while (events.size() > MAX_EVENTS) {
            events.removeFirst();
        }
    }

    private RobotState robot(String name) {
        return robots.computeIfAbsent(name, RobotState::new);
    }

    /** @return a number that changes whenever an observation arrives */
    public long version() {
        return version;
    }

    /** Where one page is: what it has been sent. */
    static final class Cursor {
        long worldVersion = -1;
        long eventSeq;
        final Map<String, Long> trailSent = new LinkedHashMap<>();
    }

    /**
     * What a page has not been sent yet, as a JSON-ready map; moves the cursor on.
     *
     * @param cursor   the page's cursor (a fresh one gets everything)
     * @param nowNanos the time now, for the page to age stale things
     * @param controls whether retract, dispose and stop are offered
     * @return the update
     */
    Map<String, Object> update(Cursor cursor, long nowNanos, Map<String, Object> controls) {
        synchronized (lock) {
            Map<String, Object> u = new LinkedHashMap<>();
            u.put("type", "update");
            u.put("title", title);
            u.put("now", nowNanos / 1e9);
            u.put("controls", controls);
            if (cursor.worldVersion != worldVersion) {
                u.put("world", world);
                cursor.worldVersion = worldVersion;
            }
            List<Map<String, Object>> rs = new ArrayList<>();
            for (RobotState r : robots.values()) {
                Map<String, Object> m = new LinkedHashMap<>();
                m.put("name", r.name);
                if (r.hasPose) {
                    m.put("pose", Map.of("x", r.x, "y", r.y, "z", r.z, "heading", r.heading, "t", r.poseNanos / 1e9, "truth", r.truth));
                }
                m.put("reachable", r.reachable);
                m.put("source", r.source);
                m.put("detail", r.detail);
                m.put("lastCommand", r.lastCommand);
                m.put("commandTime", r.commandNanos / 1e9);
                long sentUpTo = cursor.trailSent.getOrDefault(r.name, 0L);
                long total = r.trailDropped + r.trail.size();
                int from = (int) Math.max(0, sentUpTo - r.trailDropped);
                m.put("trailReset", sentUpTo == 0 || sentUpTo < r.trailDropped);
                m.put("trail", from >= r.trail.size() ? List.of() : new ArrayList<>(r.trail.subList(from, r.trail.size())));
                cursor.trailSent.put(r.name, total);
                Map<String, Object> sensors = new LinkedHashMap<>();
                r.sensors.forEach((name, s) -> sensors.put(name, Map.of("unit", s.unit, "values", new ArrayList<>(s.values))));
                m.put("sensors", sensors);
                rs.add(m);
            }
            u.put("robots", rs);
            List<HostView> byName = new ArrayList<>(hosts.values());
            byName.sort(java.util.Comparator.comparing(HostView::name).thenComparing(HostView::address));
            u.put("hosts", byName);
            List<Map<String, Object>> fresh = new ArrayList<>();
            for (Map<String, Object> e : events) {
                if ((Long) e.get("seq") > cursor.eventSeq) {
                    fresh.add(e);
                }
            }
            cursor.eventSeq = eventSeq;
            u.put("events", fresh);
            return u;
        }
    }

    /**
     * @param agentId an agent
     * @return the address of the host that last listed it, if any
     */
    public java.util.Optional<String> hostOf(String agentId) {
        synchronized (lock) {
            for (HostView h : hosts.values()) {
                for (HostView.AgentView a : h.agents()) {
                    if (a.id().equals(agentId)) {
                        return java.util.Optional.of(h.address());
                    }
                }
            }
            return java.util.Optional.empty();
        }
    }
}
