package io.robomw.platform.aibo;

import io.robomw.api.Clock;
import io.robomw.platform.command.HighLevelCommandPlatform;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * The Aibo's command platform: each high-level command goes to the URBI server as one tagged
 * background block with the {@code +end} flag ({@code c7+end: { robot.walk(0.5, 0.15) },}); its
 * {@code *** end} finishes it, a {@code !!!} error tagged with it fails it with the error's text,
 * and a command that ended here (interrupted, failed, its watchdog expired) is ended on the robot
 * with {@code stop c7,} followed by its stop text ({@code robot.stop()}), itself tagged so an
 * error in it is logged. A continuous command is refreshed by sending it again under a new tag;
 * the messages of the tags it had before are ignored.
 *
 * <p>Threads: {@link #start}, {@link #refresh} and {@link #stop} run on the execution action
 * thread and only queue bytes; the reply handlers run on the URBI reader. The current tag of each
 * run crosses between them through a concurrent map.
 */
final class AiboCommandPlatform extends HighLevelCommandPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(AiboCommandPlatform.class);

    private final UrbiConnection connection;
    private final Map<Run, String> tags = new ConcurrentHashMap<>();

    /**
     * @param robot      the robot's name
     * @param clock      the clock of the action thread
     * @param connection the URBI session
     */
    AiboCommandPlatform(String robot, Clock clock, UrbiConnection connection) {
        super(robot, clock);
        this.connection = connection;
    }

    @Override
    protected void start(Run run) {
        send(run);
    }

    @Override
    protected void refresh(Run run) {
        String old = tags.get(run);
        send(run);
        if (old != null) {
            connection.forget(old);
        }
    }

    private void send(Run run) {
        String tag = connection.newTag("c");
        tags.put(run, tag);
        connection.register(tag, reply -> onReply(run, tag, reply));
        String text = run.command().text();
        byte[] bytes;
        try {
            bytes = UrbiProtocol.command(tag, text);
        } catch (IllegalArgumentException e) {
            connection.forget(tag);
            failed(run, e.getMessage());
            return;
        }
        if (!connection.send(bytes)) {
            connection.forget(tag);
            failed(run, "it could not be sent: the link to " + connection.describe() + (connection.isDown() ? " is down" : " is congested"));
        }
    }

    private void onReply(Run run, String tag, UrbiReply reply) {
        if (!tag.equals(tags.get(run))) {
            return;
        }
        if (reply.kind() == UrbiReply.Kind.ERROR) {
            failed(run, "the robot answered \"" + UrbiProtocol.ERROR_PREFIX + " " + reply.text() + "\"");
        } else if (reply.isEnd()) {
            connection.forget(tag);
            tags.remove(run, tag);
            finished(run);
        }
    }

    /** The URBI writer has written everything queued so far (a stop's {@code stop} and stop text among it). */
    @Override
    protected java.util.concurrent.CompletableFuture<Void> sentSoFar() {
        return connection.written();
    }

    @Override
    protected void stop(Run run) {
        String tag = tags.remove(run);
        if (tag != null) {
            connection.forget(tag);
            connection.send(UrbiProtocol.stop(tag));
        }
        String stopText = run.command().stopText();
        if (!stopText.isBlank()) {
            String stopTag = connection.newTag("x");
            connection.register(stopTag, reply -> {
                if (reply.kind() == UrbiReply.Kind.ERROR) {
                    LOG.warn("robot '{}': the stop '{}' after '{}' failed: {}", robot(), stopText, run.command().name(), reply.describe());
                    connection.forget(stopTag);
                } else if (reply.isEnd()) {
                    connection.forget(stopTag);
                }
            });
            try {
                connection.send(UrbiProtocol.command(stopTag, stopText));
            } catch (IllegalArgumentException e) {
                connection.forget(stopTag);
                LOG.warn("robot '{}': the stop '{}' cannot be sent: {}", robot(), stopText, e.getMessage());
            }
        }
    }
}
