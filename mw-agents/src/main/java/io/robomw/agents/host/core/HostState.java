package io.robomw.agents.host.core;

import io.robomw.agents.host.home.AgentHandle;
import io.robomw.agents.host.messaging.HostMessaging;
import io.robomw.agents.host.protocol.FrameBuffers;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.visit.AgentPlace;
import io.robomw.agents.host.visit.HostContext;
import io.robomw.agents.host.visit.HostedAgent;
import io.robomw.agents.host.visit.SpinHandoff;
import io.robomw.agents.host.wire.WireWriter;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.store.AgentStore;
import io.robomw.agents.net.OwnerThreads;
import io.robomw.agents.net.ThrottledWarnings;
import io.robomw.api.Robot;
import io.robomw.api.spi.FailurePolicy;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.LinkedHashMap;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * What the parts of one {@link io.robomw.agents.host.AgentHost} share: who the host is, where it keeps agents, the
 * agents here ({@link #hosted}) and the ones sent from here ({@link #handles}), where agents went
 * from here, and its two thread pools (agents' stops; the home's requests of its agents).
 *
 * <p>{@link #store} and {@link #address} are set once by {@link io.robomw.agents.host.AgentHost}'s start, before the
 * host takes calls or resumes agents; the rest is fixed at construction or thread-safe.
 */
public final class HostState {

    private static final Logger LOG = LoggerFactory.getLogger(HostState.class);
    /** How many departed agents a host remembers the next host of, for calls that chase them. */
    private static final int MAX_FORWARDS = 100_000;
    /** How long a pool thread with nothing to do is kept. */
    static final long IDLE_THREAD_SECONDS = 10;

    public final String name;
    public final Robot robot;
    public final StateCodec codec;
    /** How long a call to another host may take, in milliseconds. */
    public final int timeoutMillis;
    /** The agents at this host now. */
    public final Map<UUID, HostedAgent> hosted = new ConcurrentHashMap<>();
    /** The handles of the agents whose home this host is. */
    public final Map<UUID, AgentHandle> handles = new ConcurrentHashMap<>();
    /** What happened here lately, for watchers (a console): {@link Op#WATCH}. */
    public final HostActivity activity = new HostActivity();
    /** Runs agents' stops, one pooled thread per agent at a time; its idle threads spin {@link #runnerSpinNanos} before they park while {@link #fewAgentsLately}. */
    public final ExecutorService runners;
    /** The hand-off queue of {@link #runners}: where a runner that sent a large agent on says it parks at once ({@link SpinHandoff#parkNext}). */
    public final SpinHandoff<Runnable> runnerHandoff;
    /** The arrays of large outgoing transfers, reused hop after hop. */
    public final FrameBuffers frameBuffers = new FrameBuffers();
    /** How long a runner waits for work by spinning before it parks, ns (0: never spins). */
    public final long runnerSpinNanos;
    /** How many threads {@link #runners} has: one per agent at work at once lately (an idle one ends after {@value #IDLE_THREAD_SECONDS} s). */
    private final AtomicInteger runnerThreads = new AtomicInteger();
    /**
     * The most runner threads with which the host's threads still spin: eight times the processors this JVM may use. One
     * agent going back and forth between two hosts keeps more than a few (the runner that sent it on still waits for its
     * acknowledgement as it comes back; at twice the processors its spins stopped: warm A→B→A 27 → 48 µs); a thousand
     * among four hosts keep hundreds.
     */
    private final int fewThreads = 8 * Runtime.getRuntime().availableProcessors();
    /** Compute the tags of large agent wire frames while their bytes are being written ({@link WireWriter}). */
    public final ExecutorService wireTaggers;
    /** Runs the home's calls to its agents (messages, retract and dispose requests) and clone launches. */
    public final ExecutorService requests;
    /** Where whatever the host's threads catch goes; its pools' threads report what ends them there. */
    public final FailurePolicy failures;
    private final AgentPlace place;
    private final AtomicInteger refused = new AtomicInteger();
    /** How many refusals a second are logged; a flood of them (a peer that sends garbage with a valid session) logs no more. */
    public static final int REFUSALS_LOGGED_PER_SECOND = 10;
    private final ThrottledWarnings refusals = new ThrottledWarnings(LOG, java.time.Duration.ofSeconds(1), REFUSALS_LOGGED_PER_SECOND);
    private final Map<UUID, String> forwards = new LinkedHashMap<>(256, 0.75f, false) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<UUID, String> eldest) {
            return size() > MAX_FORWARDS;
        }
    };
    public AgentStore store;
    public String address;
    /** The host's messaging; set by {@link io.robomw.agents.host.AgentHost} before the host takes calls. */
    public HostMessaging messaging;
    public volatile boolean closed;

    /**
     * @param runnerSpin how long an idle runner thread spins for the next agent before it parks ({@link SpinHandoff})
     */
    public HostState(AgentPlace place, String name, Robot robot, StateCodec codec, int timeoutMillis, java.time.Duration runnerSpin,
              FailurePolicy failures) {
        this.place = place;
        this.failures = failures;
        this.name = name;
        this.robot = robot;
        this.codec = codec;
        this.timeoutMillis = timeoutMillis;
        this.runnerSpinNanos = runnerSpin.toNanos();
        this.runnerHandoff = new SpinHandoff<>(runnerSpin, this::fewAgentsLately, System::nanoTime);
        this.runners = pool(counted(new OwnerThreads("agent-runner-" + name, failures), runnerThreads), runnerHandoff);
        this.requests = pool(new OwnerThreads("agent-requests-" + name, failures), new java.util.concurrent.SynchronousQueue<>());
        this.wireTaggers = pool(new OwnerThreads("agent-wire-tag-" + name, failures), new java.util.concurrent.SynchronousQueue<>());
    }

    /** @return a new context for an agent here, to attach to it before one of its callbacks */
    public HostContext contextOf(HostedAgent h) {
        return new HostContext(place, h);
    }

    /**
     * Counts, logs (at most {@value #REFUSALS_LOGGED_PER_SECOND} lines a second; the next line says
     * how many more there were) and answers a refused call or archive.
     */
    public Reply refuse(String why) {
        refused.incrementAndGet();
        refusals.warn("host {}: {}", name, why);
        return Reply.of(Reply.Status.REFUSED, why);
    }

    /** @return how many calls, archives and agents this host refused after the caller authenticated */
    public int refused() {
        return refused.get();
    }

    /** Remembers where an agent went from here, for calls that arrive after it left. */
    public void forwarded(UUID id, String to) {
        synchronized (forwards) {
            forwards.put(id, to);
        }
    }

    /** @return where an agent went from here, or {@code null} if this host does not remember it */
    public String forwardOf(UUID id) {
        synchronized (forwards) {
            return forwards.get(id);
        }
    }

    /**
     * @return whether the host has had few agents at work at once lately: no more runner threads
     *         (each kept {@value #IDLE_THREAD_SECONDS} s after its last agent) than eight times the
     *         processors. Only then do the host's threads spin for what comes next (an idle runner for
     *         the next agent, a runner woken for an arriving one, a runner that sent one on for its
     *         acknowledgement): one agent or a few going back and forth find a processor idle to spin
     *         on and start sooner; with many at once, every spin takes a processor from a thread with
     *         work and hops wait longer for one (docs/benchmarks.md, "Many agents at once")
     */
    public boolean fewAgentsLately() {
        return runnerThreads.get() <= fewThreads;
    }

    /** @return the factory, counting in {@code live} the threads it made that have not ended */
    private static ThreadFactory counted(ThreadFactory threads, AtomicInteger live) {
        return r -> {
            Thread t = threads.newThread(() -> {
                try {
                    r.run();
                } finally {
                    live.decrementAndGet();
                }
            });
            live.incrementAndGet();
            return t;
        };
    }

    /**
     * A pool that grows with the work (a thread per agent running at once) and gives its threads
     * back after {@value #IDLE_THREAD_SECONDS} s idle, so a burst of agents leaves no threads behind
     * on a host that runs for days.
     */
    private static ExecutorService pool(ThreadFactory threads, java.util.concurrent.BlockingQueue<Runnable> handoff) {
        return new java.util.concurrent.ThreadPoolExecutor(0, Integer.MAX_VALUE, IDLE_THREAD_SECONDS, java.util.concurrent.TimeUnit.SECONDS,
                handoff, threads);
    }
}
