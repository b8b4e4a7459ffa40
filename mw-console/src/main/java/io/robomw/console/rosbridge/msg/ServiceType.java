package io.robomw.console.rosbridge.msg;

/**
 * A service type: what a call sends and what it gets back.
 *
 * @param name       its name, {@code pkg/srv/Type}
 * @param request    the request's fields ({@code call_service}'s {@code args})
 * @param response   the response's fields ({@code service_response}'s {@code values})
 * @param definition the definition as its interface file writes it
 */
public record ServiceType(TypeName name, MessageType request, MessageType response, String definition) {
}
