package io.robomw.agents.host.rmi;

import java.rmi.Remote;
import java.rmi.RemoteException;

/**
 * What an agent host exports over RMI. Only byte arrays cross it (the export's filter refuses
 * anything else), so RMI never deserializes an object a peer chose; the host decodes and
 * authenticates every request itself.
 *
 * <p>A peer first proves it knows the cluster key: {@link #challenge()} gives a fresh nonce,
 * {@link #authenticate} takes the peer's nonce and its HMAC over both and returns a session id
 * and the host's own proof (so the peer knows it is talking to a real host). Each
 * {@link #call} then carries the session id, a sequence number and a MAC under the session key.
 */
public interface AgentHostRemote extends Remote {

    /**
     * @return a fresh 32-byte nonce, good for one {@link #authenticate} within 30 seconds
     * @throws RemoteException on a transport failure
     */
    byte[] challenge() throws RemoteException;

    /**
     * @param request the peer's name, the host's nonce, the peer's nonce and the peer's proof
     * @return a status byte; then the session id and the host's proof, or a reason
     * @throws RemoteException on a transport failure
     */
    byte[] authenticate(byte[] request) throws RemoteException;

    /**
     * @param request session id, sequence number, operation, body and MAC
     * @return status, body and MAC
     * @throws RemoteException on a transport failure
     */
    byte[] call(byte[] request) throws RemoteException;
}
