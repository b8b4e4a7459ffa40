/**
 * The Platform Layer's part of the test kit, shipped in mw-platform's test-jar for every module's
 * tests (mw-api's test-jar has the rest, {@code io.robomw.testkit}): {@link
 * io.robomw.platform.testkit.ScriptedLink}, the one fake {@link io.robomw.platform.link.Link},
 * whose far end a test plays with scripted pieces, losses and failures, or a responder that
 * {@linkplain io.robomw.platform.testkit.Answer answers} each write or each
 * {@linkplain io.robomw.platform.testkit.Framing frame}, at once, later on an injected clock, or
 * once a latch is released. A test about the wire itself uses a real one (a pseudo-terminal, a
 * TCP socket on 127.0.0.1).
 */
package io.robomw.platform.testkit;
