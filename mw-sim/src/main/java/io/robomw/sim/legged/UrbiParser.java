package io.robomw.sim.legged;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * Parses one top-level URBI statement (as {@link UrbiStatementSplitter} cuts them) into a tree,
 * for the subset of URBI 1.x the emulated Aibo answers:
 *
 * <pre>
 * statement  := [tag ('+' flag)* ':'] command
 * command    := '{' [statement (terminator statement)* [terminator]] '}'
 *             | 'stop' tag | 'every' '(' time ')' command | 'loop' command
 *             | 'motoron' | 'motoroff' | 'motors' ('on' | 'off') | 'ping'
 *             | name '=' expr (modifier ':' expr)*        headPan.val = 30 time:1000
 *             | expr                                      robot.walk(0.5, 0.15), distanceNear.val
 * expr       := term (('+' | '-') term)*
 * term       := unary (('*' | '/') unary)*
 * unary      := '-' unary | primary
 * primary    := number | time | string | name ['(' [expr (',' expr)*] ')'] | '(' expr ')'
 * name       := identifier ('.' identifier)*
 * time       := number ('ms' | 's')
 * terminator := ';' | ',' | '|' | '&amp;'
 * </pre>
 *
 * Another input is a {@link UrbiSyntaxException} with what was expected and where; the tag of the
 * statement is kept in it when it could be read, so the error can be tagged. Nesting deeper than
 * {@value #MAX_DEPTH} levels is refused. Stateless.
 */
public final class UrbiParser {

    /** The deepest nesting of blocks, parentheses and operators accepted. */
    public static final int MAX_DEPTH = 64;

    private static final Pattern TAG = Pattern.compile("\\s*([A-Za-z_][A-Za-z0-9_]{0,63})((?:\\s*\\+\\s*[A-Za-z]+)*)\\s*:(?!:)");
    private static final Set<String> KEYWORDS = Set.of("stop", "every", "loop", "motoron", "motoroff", "motors", "ping");

    private UrbiParser() {
    }

    /** A parse error, with the statement's tag when it could be read. */
    public static final class UrbiSyntaxException extends Exception {
        private static final long serialVersionUID = 1L;
        private final String tag;

        UrbiSyntaxException(String message, String tag) {
            super(message);
            this.tag = tag;
        }

        /** @return the statement's tag, or "" */
        public String tag() {
            return tag;
        }
    }

    // ---- the tree ----

    /** A statement: its tag and flags, what it does, and how it ended. */
    public record Statement(String tag, Set<String> flags, Command command, char terminator) {
        /** @return whether the next statement waits for this one ({@code ;} or {@code |}) */
        public boolean sequential() {
            return terminator == ';' || terminator == '|';
        }
    }

    /** What a statement does. */
    public sealed interface Command permits Block, Stop, Every, Loop, Keyword, Assign, Evaluate {
    }

    /** {@code { ... }}. */
    public record Block(List<Statement> statements) implements Command {
    }

    /** {@code stop tag}. */
    public record Stop(String tag) implements Command {
    }

    /** {@code every(period) command}. */
    public record Every(double periodSeconds, Statement body) implements Command {
    }

    /** {@code loop command}. */
    public record Loop(Statement body) implements Command {
    }

    /** {@code motoron}, {@code motoroff}, {@code ping}. */
    public record Keyword(String word) implements Command {
    }

    /** {@code name = value modifier:value ...}. */
    public record Assign(String target, Expr value, Map<String, Expr> modifiers) implements Command {
    }

    /** An expression whose value is printed (a read, a function call). */
    public record Evaluate(Expr expr) implements Command {
    }

    /** An expression. */
    public sealed interface Expr permits Num, Str, Ref, Call, Neg, Binary {
    }

    /**
     * A number.
     *
     * @param value the number; for a time literal ({@code 100ms}, {@code 2s}), seconds
     * @param time  whether it was written with a time unit (a bare number given as a time is
     *              milliseconds, as in URBI 1: {@code time:1000})
     */
    public record Num(double value, boolean time) implements Expr {
        /** @return it as a time in seconds: itself if written with a unit, else milliseconds */
        public double seconds() {
            return time ? value : value / 1000;
        }
    }

    /** A string. */
    public record Str(String value) implements Expr {
    }

    /** A name: a device's value ({@code headPan.val}), a variable. */
    public record Ref(String name) implements Expr {
    }

    /** A function call. */
    public record Call(String name, List<Expr> args) implements Expr {
    }

    /** {@code -x}. */
    public record Neg(Expr operand) implements Expr {
    }

    /** {@code a op b}. */
    public record Binary(char op, Expr left, Expr right) implements Expr {
    }

    // ---- parsing ----

    /**
     * @param text       a statement without its terminator
     * @param terminator the terminator that ended it
     * @return the statement
     * @throws UrbiSyntaxException if it is not in the subset
     */
    public static Statement parse(String text, char terminator) throws UrbiSyntaxException {
        Parser p = new Parser(text);
        Statement s = p.statement(terminator, 0);
        p.skipSpace();
        if (!p.atEnd()) {
            throw p.error("expected the end of the statement");
        }
        return s;
    }

    /**
     * @param text a statement
     * @return its tag, if it starts with one ({@code c12+end: ...}), or ""
     */
    public static String leadingTag(String text) {
        Matcher m = TAG.matcher(text);
        return m.lookingAt() && !KEYWORDS.contains(m.group(1)) ? m.group(1) : "";
    }

    private static final class Parser {
        private final String s;
        private int i;
        private String tag = "";

        Parser(String s) {
            this.s = s;
        }

        boolean atEnd() {
            return i >= s.length();
        }

        void skipSpace() {
            while (i < s.length() && Character.isWhitespace(s.charAt(i))) {
                i++;
            }
        }

        UrbiSyntaxException error(String what) {
            String near = i >= s.length() ? "the end" : "'" + UrbiStatementSplitter.excerpt(s.substring(i)) + "'";
            return new UrbiSyntaxException("syntax error: " + what + " at " + near + " in \"" + UrbiStatementSplitter.excerpt(s) + "\"", tag);
        }

        Statement statement(char terminator, int depth) throws UrbiSyntaxException {
            if (depth > MAX_DEPTH) {
                throw error("nesting deeper than " + MAX_DEPTH + " levels");
            }
            skipSpace();
            String ownTag = "";
            Set<String> flags = Set.of();
            Matcher m = TAG.matcher(s).region(i, s.length());
            if (m.lookingAt() && !KEYWORDS.contains(m.group(1))) {
                ownTag = m.group(1);
                if (depth == 0) {
                    tag = ownTag;
                }
                flags = new java.util.LinkedHashSet<>();
                for (String f : m.group(2).split("\\+")) {
                    String flag = f.strip();
                    if (!flag.isEmpty()) {
                        flags.add(flag);
                    }
                }
                i = m.end();
            }
            return new Statement(ownTag, Set.copyOf(flags), command(depth), terminator);
        }

        Command command(int depth) throws UrbiSyntaxException {
            skipSpace();
            if (peek('{')) {
                i++;
                List<Statement> list = new ArrayList<>();
                while (true) {
                    skipSpace();
                    if (peek('}')) {
                        i++;
                        return new Block(list);
                    }
                    Statement st = statement(';', depth + 1);
                    skipSpace();
                    char t = ';';
                    if (i < s.length() && ";,|&".indexOf(s.charAt(i)) >= 0) {
                        t = s.charAt(i++);
                    } else if (!peek('}')) {
                        throw error("expected ';', ',' or '}'");
                    }
                    list.add(new Statement(st.tag(), st.flags(), st.command(), t));
                }
            }
            int save = i;
            String word = identifier();
            if (word != null) {
                switch (word) {
                    case "stop" -> {
                        skipSpace();
                        String t = identifier();
                        if (t == null) {
                            throw error("expected the tag to stop");
                        }
                        return new Stop(t);
                    }
                    case "every" -> {
                        expect('(');
                        Expr period = expr(depth + 1);
                        expect(')');
                        double seconds = constant(period);
                        if (!(seconds > 0)) {
                            throw error("every's period must be > 0");
                        }
                        return new Every(seconds, statement(';', depth + 1));
                    }
                    case "loop" -> {
                        return new Loop(statement(';', depth + 1));
                    }
                    case "motoron", "motoroff", "ping" -> {
                        return new Keyword(word);
                    }
                    case "motors" -> {
                        skipSpace();
                        String onOff = identifier();
                        if (!"on".equals(onOff) && !"off".equals(onOff)) {
                            throw error("expected 'motors on' or 'motors off'");
                        }
                        return new Keyword("motor" + onOff);
                    }
                    default -> {
                        i = save;
                    }
                }
            }
            save = i;
            String target = name();
            if (target != null) {
                skipSpace();
                if (peek('=') && !(i + 1 < s.length() && s.charAt(i + 1) == '=')) {
                    i++;
                    Expr value = expr(depth + 1);
                    Map<String, Expr> modifiers = new LinkedHashMap<>();
                    while (true) {
                        skipSpace();
                        int at = i;
                        String mod = identifier();
                        if (mod == null) {
                            break;
                        }
                        skipSpace();
                        if (!peek(':')) {
                            i = at;
                            break;
                        }
                        i++;
                        modifiers.put(mod, expr(depth + 1));
                    }
                    return new Assign(target, value, modifiers);
                }
            }
            i = save;
            return new Evaluate(expr(depth + 1));
        }

        Expr expr(int depth) throws UrbiSyntaxException {
            if (depth > MAX_DEPTH) {
                throw error("nesting deeper than " + MAX_DEPTH + " levels");
            }
            Expr left = term(depth);
            while (true) {
                skipSpace();
                if (peek('+') || peek('-')) {
                    char op = s.charAt(i++);
                    left = new Binary(op, left, term(depth));
                } else {
                    return left;
                }
            }
        }

        Expr term(int depth) throws UrbiSyntaxException {
            Expr left = unary(depth);
            while (true) {
                skipSpace();
                if (peek('*') || peek('/')) {
                    char op = s.charAt(i++);
                    left = new Binary(op, left, unary(depth));
                } else {
                    return left;
                }
            }
        }

        Expr unary(int depth) throws UrbiSyntaxException {
            if (depth > MAX_DEPTH) {
                throw error("nesting deeper than " + MAX_DEPTH + " levels");
            }
            skipSpace();
            if (peek('-')) {
                i++;
                return new Neg(unary(depth + 1));
            }
            if (peek('+')) {
                i++;
                return unary(depth + 1);
            }
            return primary(depth);
        }

        Expr primary(int depth) throws UrbiSyntaxException {
            skipSpace();
            if (atEnd()) {
                throw error("expected a value");
            }
            char c = s.charAt(i);
            if (c == '(') {
                i++;
                Expr e = expr(depth + 1);
                expect(')');
                return e;
            }
            if (c == '"') {
                return string();
            }
            if (Character.isDigit(c) || c == '.') {
                return number();
            }
            String n = name();
            if (n == null) {
                throw error("expected a value");
            }
            skipSpace();
            if (peek('(')) {
                i++;
                List<Expr> args = new ArrayList<>();
                skipSpace();
                if (peek(')')) {
                    i++;
                    return new Call(n, args);
                }
                while (true) {
                    args.add(expr(depth + 1));
                    skipSpace();
                    if (peek(',')) {
                        i++;
                    } else if (peek(')')) {
                        i++;
                        return new Call(n, args);
                    } else {
                        throw error("expected ',' or ')' in the arguments of " + n);
                    }
                }
            }
            return new Ref(n);
        }

        Expr number() throws UrbiSyntaxException {
            int start = i;
            while (i < s.length() && (Character.isDigit(s.charAt(i)) || s.charAt(i) == '.')) {
                i++;
            }
            if (i < s.length() && (s.charAt(i) == 'e' || s.charAt(i) == 'E')) {
                int save = i;
                i++;
                if (i < s.length() && (s.charAt(i) == '+' || s.charAt(i) == '-')) {
                    i++;
                }
                if (i < s.length() && Character.isDigit(s.charAt(i))) {
                    while (i < s.length() && Character.isDigit(s.charAt(i))) {
                        i++;
                    }
                } else {
                    i = save;
                }
            }
            String digits = s.substring(start, i);
            double v;
            try {
                v = Double.parseDouble(digits);
            } catch (NumberFormatException e) {
                i = start;
                throw error("'" + digits + "' is not a number");
            }
            if (!Double.isFinite(v)) {
                i = start;
                throw error("'" + digits + "' is too large");
            }
            if (s.startsWith("ms", i) && !identifierChar(i + 2)) {
                i += 2;
                return new Num(v / 1000, true);
            }
            if (s.startsWith("s", i) && !identifierChar(i + 1)) {
                i += 1;
                return new Num(v, true);
            }
            if (i < s.length() && Character.isLetter(s.charAt(i))) {
                throw error("unknown unit");
            }
            return new Num(v, false);
        }

        Expr string() throws UrbiSyntaxException {
            StringBuilder out = new StringBuilder();
            i++;
            while (i < s.length()) {
                char c = s.charAt(i++);
                if (c == '\\' && i < s.length()) {
                    char e = s.charAt(i++);
                    out.append(switch (e) {
                        case 'n' -> '\n';
                        case 't' -> '\t';
                        default -> e;
                    });
                } else if (c == '"') {
                    return new Str(out.toString());
                } else {
                    out.append(c);
                }
            }
            throw error("a string is not closed with '\"'");
        }

        String name() {
            int start = i;
            String first = identifier();
            if (first == null) {
                return null;
            }
            StringBuilder n = new StringBuilder(first);
            while (peek('.') && identifierStart(i + 1)) {
                i++;
                n.append('.').append(identifier());
            }
            if (n.length() > 256) {
                i = start;
                return null;
            }
            return n.toString();
        }

        String identifier() {
            if (!identifierStart(i)) {
                return null;
            }
            int start = i;
            while (identifierChar(i)) {
                i++;
            }
            return s.substring(start, i);
        }

        boolean identifierStart(int at) {
            return at < s.length() && (Character.isLetter(s.charAt(at)) && s.charAt(at) < 128 || s.charAt(at) == '_');
        }

        boolean identifierChar(int at) {
            return at < s.length() && (identifierStart(at) || Character.isDigit(s.charAt(at)));
        }

        boolean peek(char c) {
            return i < s.length() && s.charAt(i) == c;
        }

        void expect(char c) throws UrbiSyntaxException {
            skipSpace();
            if (!peek(c)) {
                throw error("expected '" + c + "'");
            }
            i++;
        }

        double constant(Expr e) throws UrbiSyntaxException {
            if (e instanceof Num n) {
                return n.seconds();
            }
            if (e instanceof Neg n) {
                return -constant(n.operand());
            }
            throw error("expected a constant time, such as 100ms");
        }
    }

    /**
     * @param value a number
     * @return it as URBI prints numbers: six decimals
     */
    public static String format(double value) {
        return String.format(Locale.ROOT, "%.6f", value);
    }
}
