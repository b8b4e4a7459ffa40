package io.robomw.agents.host;

import io.robomw.api.Agent;
import io.robomw.api.AgentException;
import io.robomw.api.AgentRef;
import io.robomw.api.AgentStatus;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.Serializable;
import java.time.Duration;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.Consumer;

/** The home's handle on one of its agents; hosts' events keep it up to date. */
final class AgentHandle implements AgentRef {

    private static final Logger LOG = LoggerFactory.getLogger(AgentHandle.class);
    /** How many reports are kept for a listener not added yet (the agent may report before its sender adds one). */
    static final int MAX_EARLY_REPORTS = 10_000;

    private final AgentRequests home;
    private final UUID id;
    private final String className;
    final ClassLoader loader;
    private final CompletableFuture<Serializable> result = new CompletableFuture<>();
    private final CompletableFuture<Agent> retracted = new CompletableFuture<>();
    private final List<java.util.function.BiConsumer<String, Serializable>> reportListeners = new CopyOnWriteArrayList<>();
    /** A report and the host it was sent from. */
    private record Report(String host, Serializable value) {
    }
    /** Reports that came before the first listener was added (at most {@link #MAX_EARLY_REPORTS}); guarded by this handle. */
    private java.util.ArrayDeque<Report> earlyReports = new java.util.ArrayDeque<>();
    private final java.util.Set<Long> reportsSeen = java.util.concurrent.ConcurrentHashMap.newKeySet();
    private volatile List<io.robomw.api.Itinerary.Visit> history = List.of();
    private volatile String location;
    private volatile AgentStatus status = AgentStatus.CREATED;
    /** The last request made through this ref: the next one is sent after it has been answered. */
    private CompletableFuture<?> lastRequest = CompletableFuture.completedFuture(null);

    AgentHandle(AgentRequests home, UUID id, String className, ClassLoader loader, String firstLocation) {
        this.home = home;
        this.id = id;
        this.className = className;
        this.loader = loader;
        this.location = firstLocation;
    }

    @Override
    public UUID id() {
        return id;
    }

    @Override
    public String location() {
        return location;
    }

    @Override
    public AgentStatus status() {
        return status;
    }

    @Override
    public CompletableFuture<Serializable> result() {
        return result;
    }

    /** The first listener added also gets, first, the reports that came before it (the agent may report before its sender could add one). */
    @Override
    public void addReportListener(Consumer<Serializable> listener) {
        onReport((host, value) -> listener.accept(value));
    }

    @Override
    public void onReport(java.util.function.BiConsumer<String, Serializable> listener) {
        synchronized (this) {
            if (earlyReports != null) {
                earlyReports.forEach(r -> tell(listener, r.host(), r.value()));
                earlyReports = null;
            }
            reportListeners.add(listener);
        }
    }

    private void tell(java.util.function.BiConsumer<String, Serializable> l, String host, Serializable value) {
        try {
            l.accept(host, value);
        } catch (RuntimeException e) {
            LOG.warn("report listener of agent {} threw {}", id, e.toString());
        }
    }

    @Override
    public CompletableFuture<Agent> retract() {
        home.requestOfAgent(this, Op.RETRACT).whenComplete((ok, e) -> {
            if (e != null) {
                retracted.completeExceptionally(e);
            }
        });
        return retracted;
    }

    @Override
    public CompletableFuture<Agent> whenRetracted() {
        return retracted;
    }

    @Override
    public void dispose() {
        home.requestOfAgent(this, Op.DISPOSE).whenComplete((ok, e) -> {
            if (e != null) {
                LOG.warn("dispose of agent {} failed: {}", id, e.getMessage());
            }
        });
    }

    @Override
    public Serializable sendMessage(Serializable content, Duration timeout) {
        try {
            return sendFutureMessage(content).get(timeout.toNanos(), TimeUnit.NANOSECONDS);
        } catch (ExecutionException e) {
            if (e.getCause() instanceof AgentException a) {
                throw a;
            }
            throw new AgentException("message to agent " + id + " failed: " + e.getCause(), e.getCause());
        } catch (TimeoutException e) {
            throw new AgentException("agent " + id + " (" + className + ") did not answer a message within " + timeout.toMillis() + " ms");
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new AgentException("interrupted waiting for agent " + id + " to answer", e);
        }
    }

    @Override
    public CompletableFuture<Serializable> sendFutureMessage(Serializable content) {
        return home.messageAgent(this, content, false);
    }

    @Override
    public void sendOnewayMessage(Serializable content) {
        home.messageAgent(this, content, true);
    }

    /**
     * Runs the calls made through this ref one after the other, in the order they were made, so
     * that for example a message sent after {@link #dispose()} cannot overtake the dispose request.
     *
     * @param call     the call
     * @param executor where to run it
     * @param <T>      what it answers
     * @return its answer
     */
    synchronized <T> CompletableFuture<T> inOrder(java.util.function.Supplier<T> call, java.util.concurrent.Executor executor) {
        CompletableFuture<T> next = lastRequest.handle((r, e) -> null).thenApplyAsync(x -> call.get(), executor);
        lastRequest = next;
        return next;
    }

    @Override
    public List<io.robomw.api.Itinerary.Visit> history() {
        return history;
    }

    // ---- updates from the home ----

    void history(List<io.robomw.api.Itinerary.Visit> visits) {
        history = List.copyOf(visits);
    }

    void location(String where) {
        location = where;
    }

    void arrived(String where) {
        if (!status.equals(AgentStatus.COMPLETED) && !ended()) {
            location = where;
            status = AgentStatus.ACTIVE;
        }
    }

    /**
     * @param seq   the report's number in the agent's trip (a report delivered twice is told once)
     * @param host  the host the agent sent it from
     * @param value the value
     */
    void report(long seq, String host, Serializable value) {
        if (!reportsSeen.add(seq)) {
            return;
        }
        synchronized (this) {
            if (earlyReports != null) {
                if (earlyReports.size() == MAX_EARLY_REPORTS) {
                    earlyReports.removeFirst();
                }
                earlyReports.addLast(new Report(host, value));
                return;
            }
        }
        for (java.util.function.BiConsumer<String, Serializable> l : reportListeners) {
            tell(l, host, value);
        }
    }

    void completed(String where, Serializable value) {
        location = where;
        status = AgentStatus.COMPLETED;
        result.complete(value);
        retracted.completeExceptionally(new AgentException("agent " + id + " ended its trip at " + where + " before it could be retracted"));
    }

    void failed(String where, AgentStatus endStatus, String why) {
        location = where;
        status = endStatus;
        AgentException e = new AgentException("agent " + id + " (" + className + ") " + why);
        result.completeExceptionally(e);
        retracted.completeExceptionally(e);
    }

    void retracted(String where, Agent agent) {
        history = List.copyOf(agent.itinerary().history());
        location = where;
        status = AgentStatus.RETRACTED;
        retracted.complete(agent);
        result.completeExceptionally(new AgentException("agent " + id + " (" + className + ") was retracted; its state is the retract() result"));
    }

    boolean ended() {
        return result.isDone();
    }

    @Override
    public String toString() {
        return "AgentRef[" + className + " " + id + " " + status + " at " + location + "]";
    }
}
