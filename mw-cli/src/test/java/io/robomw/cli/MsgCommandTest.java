package io.robomw.cli;

import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import picocli.CommandLine;

import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** {@code mw msg pub|sub|send} run in this JVM against each other on loopback. */
class MsgCommandTest {

    /** Output and exit code of one run. */
    record Run(int status, String out, String err) {
    }

    private static Run mw(String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        CommandLine cl = Mw.commandLine();
        cl.setOut(new PrintWriter(out, true));
        cl.setErr(new PrintWriter(err, true));
        int status = cl.execute(args);
        return new Run(status, out.toString(), err.toString());
    }

    /** @return a file holding a topic password (mw msg takes it from a file, never from an option's value) */
    private static String passwordFile(String password) {
        try {
            java.nio.file.Path f = java.nio.file.Files.createTempFile("mw-msg-password-", "");
            f.toFile().deleteOnExit();
            java.nio.file.Files.writeString(f, password);
            return f.toString();
        } catch (IOException e) {
            throw new java.io.UncheckedIOException(e);
        }
    }

    private static int freeTcpPort() throws IOException {
        try (ServerSocket s = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            return s.getLocalPort();
        }
    }

    @Test
    void subPrintsWhatPubPublishes() throws Exception {
        String address = "tcp://127.0.0.1:" + freeTcpPort();
        CompletableFuture<Run> pub = CompletableFuture.supplyAsync(() -> mw("msg", "pub", address, "news", "hello",
                "--count", "3", "--rate", "100", "--wait-subscribers", "1", "--wait-timeout", "20"));
        Run sub = mw("msg", "sub", address, "news", "--count", "3", "--timeout", "20");
        assertEquals(0, sub.status(), sub.err());
        assertEquals(3, sub.out().split("\\[news] mw-msg data: hello", -1).length - 1, sub.out());
        assertEquals(0, pub.get(20, TimeUnit.SECONDS).status());
    }

    @Test
    void sendPrintsTheEchoOfABoundSubscriber() throws Exception {
        String address = "tcp://127.0.0.1:" + freeTcpPort();
        CompletableFuture<Run> sub = CompletableFuture.supplyAsync(() -> mw("msg", "sub", address, "cmd", "--bind", "--echo",
                "--password-file", passwordFile("pw"), "--count", "1", "--timeout", "20"));
        String pw = passwordFile("pw");
        AtomicReference<Run> sent = new AtomicReference<>();
        Await.until("the subscriber is reachable", Duration.ofSeconds(20), () -> {
            sent.set(mw("msg", "send", address, "*", "cmd", "ping", "--password-file", pw, "--timeout", "5"));
            return !sent.get().err().contains("cannot reach");
        });
        Run send = sent.get();
        assertEquals(0, send.status(), send.err());
        assertTrue(send.out().contains("reply [cmd] mw-msg echo: ping"), send.out());
        assertEquals(0, sub.get(20, TimeUnit.SECONDS).status());
    }

    @Test
    void sendToNobodyFails() throws Exception {
        Run send = mw("msg", "send", "tcp://127.0.0.1:" + freeTcpPort(), "*", "cmd", "ping", "--timeout", "1");
        assertEquals(1, send.status());
        assertTrue(send.err().contains("cannot reach"), send.err());
    }

    @Test
    void pubWaitsForASubscriberSoTheFirstPublicationIsNotLost() throws Exception {
        String address = "tcp://127.0.0.1:" + freeTcpPort();
        CompletableFuture<Run> pub = CompletableFuture.supplyAsync(() -> mw("msg", "pub", address, "news", "hello", "--wait-timeout", "20s"));
        Run sub = mw("msg", "sub", address, "news", "--count", "1", "--timeout", "20s");
        assertEquals(0, sub.status(), sub.err());
        assertTrue(sub.out().contains("[news] mw-msg data: hello"), sub.out());
        Run published = pub.get(20, TimeUnit.SECONDS);
        assertEquals(0, published.status(), published.err());
        // (it says "waiting up to 20s for a subscriber" first unless the subscriber was already there when it bound)
        assertTrue(published.out().contains("published #1: hello (1 subscriber)"), published.out());
    }

    @Test
    void pubSaysWhenItHadNoSubscriber() throws Exception {
        String address = "tcp://127.0.0.1:" + freeTcpPort();
        Run waited = mw("msg", "pub", address, "news", "hello", "--wait-timeout", "200ms");
        assertEquals(1, waited.status());
        assertTrue(waited.err().contains("no subscriber came to " + address + " within 200ms; nothing was published"), waited.err());
        Run toNobody = mw("msg", "pub", "tcp://127.0.0.1:" + freeTcpPort(), "news", "hello", "--wait-subscribers", "0");
        assertEquals(0, toNobody.status(), toNobody.err());
        assertTrue(toNobody.out().contains("published #1: hello (0 subscribers)"), toNobody.out());
        assertTrue(toNobody.err().contains("no subscriber was connected, so nobody received it"), toNobody.err());
    }

    @Test
    void sendSaysTheReceiverRefusedAWrongOrMissingPassword() throws Exception {
        String address = "tcp://127.0.0.1:" + freeTcpPort();
        CompletableFuture<Run> sub = CompletableFuture.supplyAsync(() -> mw("msg", "sub", address, "cmd", "--bind", "--echo",
                "--password-file", passwordFile("right"), "--count", "1", "--timeout", "20s"));
        String wrongPassword = passwordFile("wrong");
        AtomicReference<Run> sent = new AtomicReference<>();
        Await.until("the subscriber is reachable", Duration.ofSeconds(20), () -> {
            sent.set(mw("msg", "send", address, "*", "cmd", "ping", "--password-file", wrongPassword, "--timeout", "5s"));
            return !sent.get().err().contains("cannot reach");
        });
        Run wrong = sent.get();
        assertEquals(1, wrong.status());
        assertTrue(wrong.err().contains("topic 'cmd' is password-protected and the message had a wrong password"), wrong.err());
        Run missing = mw("msg", "send", address, "*", "cmd", "ping", "--timeout", "5s");
        assertEquals(1, missing.status());
        assertTrue(missing.err().contains("the message had no password"), missing.err());
        assertEquals(0, mw("msg", "send", address, "*", "cmd", "ping", "--password-file", passwordFile("right")).status());
        assertEquals(0, sub.get(20, TimeUnit.SECONDS).status());
    }

    @Test
    void pubRefusesToCountSubscribersThroughABroker() throws Exception {
        Run pub = mw("msg", "pub", "mqtt://127.0.0.1:" + freeTcpPort(), "news", "hi", "--wait-subscribers", "1");
        assertEquals(2, pub.status());
        assertTrue(pub.err().contains("through a broker"), pub.err());
    }
}
