/**
 * What the parts of one running agent host share ({@link io.robomw.agents.host.core.HostState}),
 * the dispatch of verified calls to them ({@link io.robomw.agents.host.core.Calls}), agents' code,
 * and the activity watchers see. Internal to the agent host.
 */
package io.robomw.agents.host.core;
