package io.robomw.agents.messaging.rmi;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;

import javax.net.ssl.SSLContext;
import java.io.IOException;
import java.io.ObjectInputFilter;
import java.net.InetAddress;
import java.rmi.NotBoundException;
import java.rmi.RemoteException;
import java.rmi.registry.LocateRegistry;
import java.rmi.registry.Registry;
import java.rmi.server.ExportException;
import java.rmi.server.UnicastRemoteObject;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * RMI for one node. Binding creates the registry on the address's port (or uses the one this JVM
 * already has there) and exports the endpoint on the same port, listening on the address's host
 * only. Calls into the endpoint are deserialized through a filter that admits byte arrays and
 * numbers only. Thread-safe.
 */
final class RmiTransport implements Transport {

    /**
     * What may be deserialized in calls to a {@link FrameEndpoint}: its arguments are a long and a
     * byte array of at most one outbound buffer's bytes (a client never delivers more at once).
     *
     * @param settings the node's settings
     * @return the filter
     */
    static ObjectInputFilter callFilter(io.robomw.agents.messaging.MessagingSettings settings) {
        return ObjectInputFilter.Config.createFilter("maxdepth=3;maxarray=" + Math.max(settings.outboundBufferBytes(), settings.maxFrameSize())
                + ";[B;!*");
    }

    private final TransportContext context;
    private final List<AutoCloseable> open = new CopyOnWriteArrayList<>();
    private SSLContext tls;

    RmiTransport(TransportContext context) {
        this.context = context;
    }

    @Override
    public Endpoint bind(Address address) throws IOException {
        if (address.path().isEmpty()) {
            throw new IOException("an rmi address needs a name: rmi://host:port/name, got " + address);
        }
        SSLContext ssl = tls();
        RmiSockets.Server ssf = new RmiSockets.Server(InetAddress.getByName(address.host()), ssl);
        RmiSockets.Client csf = new RmiSockets.Client(address.host(), ssl != null, (int) context.settings().connectTimeout().toMillis());
        Registry registry;
        boolean own;
        int port;
        try {
            registry = LocateRegistry.createRegistry(address.port(), csf, ssf);
            own = true;
            port = address.port() == 0 ? ssf.boundPort() : address.port();
        } catch (ExportException e) {
            if (address.port() == 0) {
                throw e;
            }
            registry = LocateRegistry.getRegistry(address.host(), address.port(), csf);
            own = false;
            port = address.port();
        }
        Address bound = address.withPort(port);
        RmiEndpoint endpoint = new RmiEndpoint(bound, context, registry, own);
        try {
            FrameEndpoint stub = (FrameEndpoint) UnicastRemoteObject.exportObject(endpoint, own ? address.port() : 0, csf, ssf, callFilter(context.settings()));
            registry.rebind(address.path(), stub);
        } catch (RemoteException e) {
            endpoint.close();
            throw new IOException("cannot export " + bound + ": " + e.getMessage(), e);
        }
        open.add(endpoint);
        return endpoint;
    }

    @Override
    public Link connect(Address address) throws IOException {
        if (address.path().isEmpty()) {
            throw new IOException("an rmi address needs a name: rmi://host:port/name, got " + address);
        }
        boolean useTls = context.settings().tls() != null;
        RmiSockets.Client csf = new RmiSockets.Client(address.host(), useTls, (int) context.settings().connectTimeout().toMillis());
        FrameEndpoint remote;
        long session;
        try {
            Registry registry = LocateRegistry.getRegistry(address.host(), address.port(), csf);
            remote = (FrameEndpoint) registry.lookup(address.path());
            session = remote.open(context.nodeName());
        } catch (NotBoundException e) {
            throw new IOException("nothing is bound as '" + address.path() + "' in the RMI registry at " + address.endpoint(), e);
        } catch (RemoteException | ClassCastException e) {
            throw new IOException("cannot reach " + address + ": " + io.robomw.agents.net.RmiSocketSetup.reason(e), e);
        }
        RmiLink link = new RmiLink(address, remote, session, context, open::remove);
        open.add(link);
        link.start();
        return link;
    }

    @Override
    public void close() {
        for (AutoCloseable c : List.copyOf(open)) {
            try {
                c.close();
            } catch (Exception e) {
                // closing anyway
            }
        }
        open.clear();
    }

    private synchronized SSLContext tls() throws IOException {
        if (tls == null && context.settings().tls() != null) {
            tls = context.settings().tls().context();
        }
        return tls;
    }
}
