package io.robomw.agents.host.protocol;

import java.io.PrintWriter;
import java.io.StringWriter;

/** A failure as it travels home in a visit's detail: its text, then its stack trace, cut to a size a visit can carry. */
public final class StackTraces {

    private StackTraces() {
    }

    /** @return the throwable's text and stack trace (with its causes), at most {@link Bodies#MAX_DETAIL_CHARS} characters */
    public static String of(Throwable t) {
        StringWriter w = new StringWriter();
        t.printStackTrace(new PrintWriter(w));
        String trace = w.toString().stripTrailing();
        return trace.length() > Bodies.MAX_DETAIL_CHARS ? trace.substring(0, Bodies.MAX_DETAIL_CHARS) + "\n\t..." : trace;
    }

    /** @return the first line of a detail: the failure's text without its trace */
    public static String firstLine(String detail) {
        int nl = detail.indexOf('\n');
        return nl < 0 ? detail : detail.substring(0, nl);
    }
}
