package io.robomw.agents.messaging.rmi;

import java.rmi.Remote;
import java.rmi.RemoteException;

/**
 * The remote object an RMI endpoint exports: clients open a session, deliver batches of frames,
 * and poll for the frames waiting for them (replies, publications). Only byte arrays and numbers
 * cross it, so its deserialization filter admits nothing else. Clients never export objects of
 * their own, so they need no listening port.
 */
public interface FrameEndpoint extends Remote {

    /**
     * @param peerName the client node's name, for logs
     * @return a new session id (random; it is the session's only credential besides TLS)
     * @throws RemoteException if the call fails
     */
    long open(String peerName) throws RemoteException;

    /**
     * @param session a session id
     * @param frames  frames back to back
     * @throws RemoteException if the call fails, or the session is unknown ({@link java.rmi.NoSuchObjectException})
     */
    void deliver(long session, byte[] frames) throws RemoteException;

    /**
     * @param session       a session id
     * @param maxWaitMillis how long to wait when nothing is waiting
     * @return the frames waiting for the session, back to back; empty if none came in time
     * @throws RemoteException if the call fails, or the session is unknown
     */
    byte[] poll(long session, long maxWaitMillis) throws RemoteException;

    /**
     * @param session a session id
     * @throws RemoteException if the call fails
     */
    void close(long session) throws RemoteException;
}
