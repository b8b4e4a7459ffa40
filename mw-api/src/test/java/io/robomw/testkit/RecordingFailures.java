package io.robomw.testkit;

import io.robomw.api.spi.FailurePolicy;

import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * A failure policy for tests: keeps every report (who, what, whether the thread died) and counts
 * them, as the injected policy of an owner thread (a simulation, an emulator's link, an agent host).
 */
public final class RecordingFailures implements FailurePolicy {

    /**
     * One report.
     *
     * @param owner   the owner thread's role
     * @param failure what it caught
     * @param died    whether the thread died of it
     */
    public record Report(String owner, Throwable failure, boolean died) {
    }

    private final List<Report> reports = new CopyOnWriteArrayList<>();

    @Override
    public void survived(String owner, Throwable failure) {
        reports.add(new Report(owner, failure, false));
    }

    @Override
    public void died(String owner, Throwable failure) {
        reports.add(new Report(owner, failure, true));
    }

    @Override
    public long count() {
        return reports.size();
    }

    /** @return every report so far, in order */
    public List<Report> reports() {
        return List.copyOf(reports);
    }

    /** @return the deaths reported so far */
    public List<Report> deaths() {
        return reports.stream().filter(Report::died).toList();
    }

    /** @return the survived failures reported so far */
    public List<Report> survived() {
        return reports.stream().filter(r -> !r.died()).toList();
    }
}
