package io.robomw.cli;

import io.robomw.agents.host.ops.HostClient;
import picocli.CommandLine.Command;

import java.io.IOException;

/** {@code mw retract ID HOST...}: sends an agent home, after the callback it is in. */
@Command(name = "retract", mixinStandardHelpOptions = true,
        description = {"Sends an agent home: it finishes the callback it is in, and its state goes to its home (the program or host that sent it).",
                "Example: mw retract 3f2b9c1e-5d7a-4e61-9b0f-2a8c4d6e8f10 rmi://127.0.0.1:1099/nxt"})
final class RetractCommand extends AgentRequestCommand {

    @Override
    HostClient.Taken ask(HostClient client, String host) throws IOException {
        return client.retract(host, id);
    }

    @Override
    String effect() {
        return "goes home when its current callback returns: retract taken";
    }
}
