/**
 * Authenticated calls between hosts: the RMI endpoint that proves peers and checks every call
 * ({@link io.robomw.agents.host.rmi.HostEndpoint}), its sockets and connection limits, sessions, and
 * the links a host keeps to its peers ({@link io.robomw.agents.host.rmi.Peers}). Internal to the
 * agent host ({@link io.robomw.agents.host.rmi.AgentHostRemote} is public because RMI needs it).
 */
package io.robomw.agents.host.rmi;
