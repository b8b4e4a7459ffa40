package io.robomw.console.source;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.ops.HostWatch;
import io.robomw.console.observe.HostView;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * Watches one agent host on a thread of its own ({@link HostWatch}, authenticated with the cluster
 * key): every period, what the host says becomes a {@link Observation.HostSeen} and its new events
 * {@link Observation.AgentEvent}s. A host that does not answer is reported down with the agents it
 * last listed (stale) and asked again at the next period, so it shows up again when it is back.
 */
public final class HostWatcher implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(HostWatcher.class);

    private final HostWatch watch;
    private final Observer observer;
    private final Duration period;
    private final Thread thread;
    private final FailurePolicy failures;
    private final CountDownLatch closed = new CountDownLatch(1);
    private volatile HostView last;
    private boolean wasDown;

    private HostWatcher(HostWatch watch, Observer observer, Duration period, FailurePolicy failures) {
        this.watch = watch;
        this.failures = failures;
        this.observer = observer;
        this.period = period;
        String address = watch.address();
        this.last = new HostView(address, address.substring(address.lastIndexOf('/') + 1), false, null, List.of(), null, "not asked yet", 0);
        this.thread = new Thread(this::run, "console-host-" + last.name()); // run() catches whatever ends it, in one place
        thread.setDaemon(true);
    }

    /**
     * @param address  the host
     * @param key      the cluster key
     * @param useTls   whether the host uses TLS
     * @param observer who is told
     * @param period   time between two looks
     * @param failures where a failed look (reported as survived; the next period looks again) and
     *                 what ends the watcher go
     * @return the running watcher
     */
    public static HostWatcher watch(String address, ClusterKey key, boolean useTls, Observer observer, Duration period, FailurePolicy failures) {
        HostWatcher w = new HostWatcher(HostWatch.of(address, key, useTls, "console-" + ProcessHandle.current().pid()), observer, period, failures);
        w.thread.start();
        return w;
    }

    /** @return the host's address */
    public String address() {
        return watch.address();
    }

    /** @return the host as last seen */
    public HostView last() {
        return last;
    }

    private void run() {
        try {
            do {
                try {
                    look();
                } catch (Throwable e) {
                    // one look failed (what the host said, or an observer): reported, and the next period looks again
                    failures.surviveOrRethrow(thread.getName(), e);
                }
            } while (!closed.await(period.toMillis(), TimeUnit.MILLISECONDS));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } catch (Throwable t) {
            LOG.warn("console: watching host {} failed; no more updates of it: {}", watch.address(), t.toString());
            failures.died(thread.getName(), t);
            observer.observe(new Observation.HostSeen(now(), last.down("the console stopped watching it: " + t)));
        }
    }

    private void look() {
        long t = now();
        HostWatch.Snapshot s;
        try {
            s = watch.poll();
        } catch (IOException e) {
            if (!wasDown) {
                LOG.info("console: host {} does not answer: {}", watch.address(), e.getMessage());
            }
            wasDown = true;
            last = last.down(String.valueOf(e.getMessage()));
            observer.observe(new Observation.HostSeen(t, last));
            return;
        }
        if (wasDown) {
            LOG.info("console: host {} answers again", watch.address());
        }
        wasDown = false;
        if (s.missed() > 0) {
            observer.observe(new Observation.AgentEvent(t, new UUID(0, 0).toString(), "", "missed", watch.address(),
                    s.missed() + " events happened at this host while the console could not ask it"));
        }
        List<HostView.AgentView> agents = new ArrayList<>();
        for (HostWatch.Agent a : s.agents()) {
            List<HostView.StopView> stops = a.itinerary() == null ? null
                    : a.itinerary().stream().map(x -> new HostView.StopView(x.host(), x.outcome(), x.detail(), x.round())).toList();
            agents.add(new HostView.AgentView(a.id().toString(), a.className(), a.status(), a.hop(), a.home(), stops, a.current()));
        }
        List<HostView.OwedDelivery> owed = s.owed() == null ? null
                : s.owed().stream().map(o -> new HostView.OwedDelivery(o.home(), o.count(), o.oldestMillis() * 1_000_000L)).toList();
        last = new HostView(watch.address(), s.name(), true, s.robot(), agents, owed, "", t);
        for (HostWatch.Event e : s.events()) {
            observer.observe(new Observation.AgentEvent(e.timeMillis() * 1_000_000L, e.agent().toString(), e.className(), e.kind(), e.host(), e.detail()));
        }
        observer.observe(new Observation.HostSeen(t, last));
    }

    /**
     * Asks the host which hosts it knows (and who it is), over this watcher's link: no new session.
     *
     * @return what the host says of itself
     * @throws IOException if it cannot be reached, refuses this console, or answers nonsense
     */
    public io.robomw.agents.host.HostDescription describe() throws IOException {
        return watch.describe();
    }

    /**
     * @param agent an agent at this host
     * @return what happened
     * @throws IOException if no host took the request
     */
    public String retract(UUID agent) throws IOException {
        return "retract of agent " + agent + " sent to " + watch.retract(watch.address(), agent) + "; it goes home when its current callback returns";
    }

    /**
     * @param agent an agent at this host
     * @return what happened
     * @throws IOException if no host took the request
     */
    public String dispose(UUID agent) throws IOException {
        return "dispose of agent " + agent + " sent to " + watch.dispose(watch.address(), agent) + "; its trip ends when its current callback returns";
    }

    private static long now() {
        return System.currentTimeMillis() * 1_000_000L;
    }

    @Override
    public void close() {
        closed.countDown();
        thread.interrupt();
        try {
            thread.join(5_000);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        watch.close();
    }
}
