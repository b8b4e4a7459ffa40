package io.robomw.it.soak;

import java.io.IOException;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** What every soak run must show (docs/reliability.md states the same bounds). */
final class SoakChecks {

    private SoakChecks() {
    }

    static void check(Soak.Figures f) throws IOException {
        String what = Soak.describe(f);
        assertEquals(0, f.lost(), "agents lost: " + what);
        assertEquals(0, f.stopsRunTwice(), "stops run twice: " + what);
        assertEquals(0, f.reportsLost(), "reports lost: " + what);
        assertEquals(0, f.reportsDuplicate(), "reports duplicated at the home: " + what);
        assertTrue(f.stopsRun() > f.sent(), "the agents went round: " + what);
        for (Soak.HostRow r : f.rows()) {
            assertTrue(r.after().threads() <= r.before().threads() + Soak.THREAD_BOUND, "threads of " + r.host() + ": " + what);
            assertTrue(r.after().files() <= r.before().files() + Soak.FILE_BOUND, "files of " + r.host() + ": " + what);
            assertTrue(r.after().heapKiB() <= r.before().heapKiB() + Soak.HEAP_BOUND_KIB, "heap of " + r.host() + ": " + what);
        }
    }
}
