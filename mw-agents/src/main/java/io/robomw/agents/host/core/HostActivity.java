package io.robomw.agents.host.core;

import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.ops.HostWatch;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.visit.HostedAgent;
import io.robomw.api.Itinerary;

import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Collection;
import java.util.Deque;
import java.util.List;
import java.util.UUID;

/**
 * What happened at this host lately, for watchers ({@link HostWatch}, the console): agents
 * arriving, stops done or failed, reports sent home, departures, trips ending. A bounded ring of
 * the last {@value #CAPACITY} events, each numbered, so a watcher asks for what came after the
 * last number it saw and a watcher that fell behind learns how many it missed. Thread-safe.
 *
 * <p>It also writes the answer to {@link Op#WATCH} (layout in {@link HostWatch}): the host's name
 * and robot, its agents with their itineraries, and the events after a number.
 */
public final class HostActivity {

    static final int CAPACITY = 1_000;
    /** Visits of an itinerary sent to watchers: the latest ones (a repeated itinerary's history grows without end). */
    static final int MAX_VISITS = 20;
    /** Longest detail kept per event, characters (a report's text is cut there). */
    static final int MAX_DETAIL = 300;

    /** Kinds of event, as written on the wire (by name). */
    public static final String ARRIVED = "arrived";
    public static final String STOP_DONE = "stop-done";
    public static final String STOP_FAILED = "stop-failed";
    public static final String REPORT = "report";
    public static final String DEPARTED = "departed";
    public static final String RESULT = "result";
    public static final String FAILED = "failed";
    public static final String DISPOSED = "disposed";
    public static final String RETRACTED = "retracted";

    private record Event(long seq, long timeMillis, UUID agent, String className, String kind, String host, String detail) {
    }

    private final Deque<Event> events = new ArrayDeque<>();
    private long nextSeq = 1;

    /**
     * Records an event.
     *
     * @param agent     the agent
     * @param className its class
     * @param kind      one of the kinds above
     * @param host      where (this host's address)
     * @param detail    the stop's failure, the report's text, the next host...
     */
    public synchronized void record(UUID agent, String className, String kind, String host, String detail) {
        String d = detail == null ? "" : detail.length() > MAX_DETAIL ? detail.substring(0, MAX_DETAIL) + "…" : detail;
        events.addLast(new Event(nextSeq++, System.currentTimeMillis(), agent, className, kind, host == null ? "" : host, d));
        while (events.size() > CAPACITY) {
            events.removeFirst();
        }
    }

    /** @param value a report @return its text for watchers, never throwing (it is the agent's code) */
    public static String describe(Object value) {
        try {
            return String.valueOf(value);
        } catch (Throwable e) {
            io.robomw.agents.net.OwnerThreads.rethrowFatal(e);
            return "(a " + value.getClass().getName() + " whose toString() threw " + e + ")";
        }
    }

    /**
     * The answer to {@link Op#WATCH}.
     *
     * @param hostName  this host's name
     * @param robotName its robot's name, "" for none
     * @param agents    the agents here
     * @param since     the last event number the watcher has seen
     * @return the body
     */
    public byte[] watchReply(String hostName, String robotName, Collection<HostedAgent> agents, long since) {
        return watchReply(hostName, robotName, agents, since, null);
    }

    /**
     * The answer to {@link Op#WATCH}, with the deliveries the host owes agents' homes (tag 4: per
     * home, how many and since when the oldest is owed).
     *
     * @param owed what the host owes, or {@code null} to leave the section out
     */
    public byte[] watchReply(String hostName, String robotName, Collection<HostedAgent> agents, long since, List<OwedDelivery> owed) {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeByte(HostWatch.FORMAT_VERSION);
            section(out, HostWatch.SECTION_HOST, s -> {
                s.writeUTF(hostName);
                s.writeUTF(robotName);
            });
            section(out, HostWatch.SECTION_AGENTS, s -> {
                List<HostedAgent> list = new ArrayList<>(agents);
                s.writeInt(list.size());
                for (HostedAgent h : list) {
                    s.writeLong(h.id.getMostSignificantBits());
                    s.writeLong(h.id.getLeastSignificantBits());
                    s.writeUTF(h.className);
                    s.writeUTF(h.status.name());
                    s.writeLong(h.hop);
                    s.writeUTF(h.home);
                    writeItinerary(s, h);
                }
            });
            List<Event> fresh;
            long next;
            synchronized (this) {
                fresh = events.stream().filter(e -> e.seq() > since).toList();
                next = nextSeq;
            }
            section(out, HostWatch.SECTION_EVENTS, s -> {
                s.writeLong(next);
                s.writeInt(fresh.size());
                for (Event e : fresh) {
                    s.writeLong(e.seq());
                    s.writeLong(e.timeMillis());
                    s.writeLong(e.agent().getMostSignificantBits());
                    s.writeLong(e.agent().getLeastSignificantBits());
                    s.writeUTF(e.className());
                    s.writeUTF(e.kind());
                    s.writeUTF(e.host());
                    s.writeUTF(e.detail());
                }
            });
            if (owed != null) {
                java.util.Map<String, long[]> byHome = new java.util.TreeMap<>(); // home -> {count, oldest millis}
                for (OwedDelivery o : owed) {
                    long[] c = byHome.computeIfAbsent(o.home(), k -> new long[] {0, Long.MAX_VALUE});
                    c[0]++;
                    c[1] = Math.min(c[1], o.owedSince().toEpochMilli());
                }
                section(out, HostWatch.SECTION_OWED, s -> {
                    s.writeInt(byHome.size());
                    for (java.util.Map.Entry<String, long[]> e : byHome.entrySet()) {
                        s.writeUTF(e.getKey());
                        s.writeInt((int) Math.min(Integer.MAX_VALUE, e.getValue()[0]));
                        s.writeLong(e.getValue()[1]);
                    }
                });
            }
            out.flush();
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * The itinerary as a watcher shows it: the latest {@value #MAX_VISITS} visits made (with
     * outcomes), the stop the agent is at, then the stops ahead. The agent's own thread may be changing it: a copy that fails is
     * sent as "not known" this time.
     */
    private static void writeItinerary(DataOutputStream s, HostedAgent h) throws IOException {
        List<Itinerary.Visit> visits;
        List<Itinerary.Stop> stops;
        int current;
        try {
            Itinerary it = h.agent.itinerary();
            visits = it.history();
            visits = visits.subList(Math.max(0, visits.size() - MAX_VISITS), visits.size());
            stops = it.stops();
            current = it.currentIndex();
        } catch (RuntimeException e) {
            s.writeBoolean(false);
            return;
        }
        s.writeBoolean(true);
        int ahead = Math.max(0, stops.size() - Math.max(0, current));
        s.writeInt(visits.size() + ahead);
        for (Itinerary.Visit v : visits) {
            s.writeUTF(v.host());
            s.writeUTF(v.outcome().name());
            s.writeUTF(v.detail() == null ? "" : v.detail().length() > MAX_DETAIL ? v.detail().substring(0, MAX_DETAIL) + "…" : v.detail());
            s.writeInt(v.round());
        }
        for (int i = Math.max(0, current); i < stops.size(); i++) {
            s.writeUTF(stops.get(i).host());
            s.writeUTF("");
            s.writeUTF("");
            s.writeInt(0);
        }
        s.writeInt(current >= 0 && current < stops.size() ? visits.size() : -1);
    }

    private interface SectionWriter {
        void write(DataOutputStream out) throws IOException;
    }

    private static void section(DataOutputStream out, int tag, SectionWriter w) throws IOException {
        ByteArrayOutputStream b = new ByteArrayOutputStream();
        DataOutputStream s = new DataOutputStream(b);
        w.write(s);
        s.flush();
        out.writeByte(tag);
        out.writeInt(b.size());
        b.writeTo(out);
    }
}
