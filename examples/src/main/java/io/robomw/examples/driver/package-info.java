/**
 * An example driver, as docs/writing-a-driver.md builds it: the LineBot, a made-up hobby robot
 * board that speaks a line protocol over a serial port. {@link io.robomw.examples.driver.LineBotProtocol}
 * is the codec, {@link io.robomw.examples.driver.LineBot} one board behind its channel,
 * {@link io.robomw.examples.driver.LineBotMotorDriver} and
 * {@link io.robomw.examples.driver.LineBotSensorPlatform} its motors and sensors, and
 * {@link io.robomw.examples.driver.LineBotPlatformProvider} what {@code platform: linebot} finds
 * through {@link java.util.ServiceLoader}.
 */
package io.robomw.examples.driver;
