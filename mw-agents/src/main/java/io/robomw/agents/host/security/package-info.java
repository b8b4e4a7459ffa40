/**
 * How calls and agent wire frames are authenticated once a session is agreed: HMAC-SHA256 or
 * AES-256-GCM tags, computed while the bytes are written. Internal to the agent host.
 */
package io.robomw.agents.host.security;
