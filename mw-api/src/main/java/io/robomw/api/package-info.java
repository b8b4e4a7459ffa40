/**
 * The Instruction Layer of RoboMW: everything an application or a mobile agent touches.
 *
 * <h2>Units and signs</h2>
 * Every value is in SI units: metres, radians, seconds, metres per second, radians per second.
 * A positive distance drives forwards; a positive angle turns to the left (anti-clockwise seen
 * from above), which increases the heading. Where a value leaves SI, its unit is in its name
 * ({@code degreesPerSecond}, {@link io.robomw.api.ReturnType#CENTIMETERS}).
 *
 * <h2>Blocking</h2>
 * Every motion and sensing verb has two forms with two names: the plain verb ({@code move},
 * {@code turn}, {@code getValue}) blocks until the action is done; the {@code ...Async} form
 * returns at once with a {@link java.util.concurrent.CompletableFuture}.
 *
 * <h2>Entry points</h2>
 * {@link io.robomw.api.Robots#open(java.nio.file.Path)} opens a robot from its YAML description;
 * the returned {@link io.robomw.api.Robot} is the whole API.
 */
package io.robomw.api;
