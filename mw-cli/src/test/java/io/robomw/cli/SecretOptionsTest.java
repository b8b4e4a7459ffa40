package io.robomw.cli;

import org.junit.jupiter.api.Test;
import picocli.CommandLine;

import java.io.PrintWriter;
import java.io.StringWriter;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37: a secret given as an option's value shows in {@code ps} to every user of the machine,
 * so the options that took one are refused, saying what to use instead, and never repeat the value.
 */
class SecretOptionsTest {

    private static String refusal(String... args) {
        StringWriter err = new StringWriter();
        CommandLine cl = Mw.commandLine();
        cl.setOut(new PrintWriter(new StringWriter(), true));
        cl.setErr(new PrintWriter(err, true));
        assertEquals(2, cl.execute(args), "refused as a usage error");
        return err.toString();
    }

    @Test
    void theOptionsThatTookASecretAreRefusedNamingTheFileOptionAndTheVariable() {
        String serve = refusal("host", "--name", "h", "--serve", "tcp://127.0.0.1:0", "--serve-password", "s3cret-value");
        assertTrue(serve.contains("--serve-password is no longer taken") && serve.contains("--serve-password-file FILE")
                && serve.contains(Secrets.SERVE_PASSWORD_ENV), serve);
        String tls = refusal("agents", "--tls-password", "s3cret-value", "rmi://127.0.0.1:1099/h");
        assertTrue(tls.contains("--tls-password-file FILE") && tls.contains(Secrets.TLS_PASSWORD_ENV), tls);
        String topic = refusal("msg", "send", "tcp://127.0.0.1:1", "*", "cmd", "ping", "--password", "s3cret-value");
        assertTrue(topic.contains("--password-file FILE") && topic.contains(Secrets.TOPIC_PASSWORD_ENV), topic);
        for (String e : new String[] {serve, tls, topic}) {
            assertFalse(e.contains("s3cret-value"), "the refusal does not repeat the secret: " + e);
        }
    }
}
