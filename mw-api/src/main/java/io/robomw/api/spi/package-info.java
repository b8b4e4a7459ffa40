/**
 * The service provider interface between the layers. The Configuration Layer drives a robot
 * platform through {@link io.robomw.api.spi.RobotPlatform}; platforms (brick drivers, the
 * simulator) offer themselves through {@link io.robomw.api.spi.PlatformProvider}, found by
 * {@link java.util.ServiceLoader} from the {@code platform:} value of a robot description.
 *
 * <p>Below this line everything is in motor degrees and raw sensor values; above it, in metres,
 * radians and the units of {@link io.robomw.api.ReturnType}. The one exception is a platform that
 * moves by its firmware's own commands (a legged robot): it also implements
 * {@link io.robomw.api.spi.HighLevelPlatform} and takes {@link io.robomw.api.spi.HighLevelCommand}s,
 * text in its own language rendered from the description's templates, with their SI arguments.
 */
package io.robomw.api.spi;
