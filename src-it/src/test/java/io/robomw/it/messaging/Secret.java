package io.robomw.it.messaging;

import java.io.Serializable;

/** A payload class that no peer puts on its allow-list. @param text anything */
public record Secret(String text) implements Serializable {
}
