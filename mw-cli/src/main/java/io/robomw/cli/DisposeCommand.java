package io.robomw.cli;

import io.robomw.agents.host.ops.HostClient;
import picocli.CommandLine.Command;

import java.io.IOException;

/** {@code mw dispose ID HOST...}: ends an agent's trip where it is, after the callback it is in. */
@Command(name = "dispose", mixinStandardHelpOptions = true,
        description = {"Ends an agent's trip where it is, after the callback it is in; its home is told it was disposed of.",
                "Example: mw dispose 3f2b9c1e-5d7a-4e61-9b0f-2a8c4d6e8f10 rmi://127.0.0.1:1099/nxt"})
final class DisposeCommand extends AgentRequestCommand {

    @Override
    HostClient.Taken ask(HostClient client, String host) throws IOException {
        return client.dispose(host, id);
    }

    @Override
    String effect() {
        return "ends its trip when its current callback returns: dispose taken";
    }
}
