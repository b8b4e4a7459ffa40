package io.robomw.cli;

import java.io.IOException;
import java.io.PrintWriter;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;

/**
 * The port of a command's web page: the one given with {@code --port}, else the default if it is
 * free, else a free one, said on standard error (as Jupyter and Vite do when their port is taken:
 * a second {@code mw console} beside the first just works). A port given explicitly is never
 * replaced: if it is taken the page fails to start, naming it.
 */
final class PagePort {

    private PagePort() {
    }

    /**
     * @param bind     the page's address
     * @param port     the port asked for (the option's value)
     * @param explicit whether the user gave it
     * @param err      where to say that another was chosen
     * @param command  the command, for that line
     * @return the port to bind: {@code port}, or 0 (a free one) when the default is taken
     */
    static int choose(String bind, int port, boolean explicit, PrintWriter err, String command) {
        if (explicit || port == 0 || free(bind, port)) {
            return port;
        }
        err.println(command + ": port " + port + " on " + bind + " is taken; the page takes a free port instead (--port chooses one)");
        err.flush();
        return 0;
    }

    private static boolean free(String bind, int port) {
        try (ServerSocket s = new ServerSocket()) {
            s.setReuseAddress(true);
            s.bind(new InetSocketAddress(InetAddress.getByName(bind), port));
            return true;
        } catch (IOException e) {
            return false;
        }
    }
}
