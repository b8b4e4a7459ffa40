package io.robomw.sim.emulator.mavlink;

/**
 * One item of a mission as MISSION_ITEM_INT carries it.
 *
 * @param seq          its place, from 0 (ArduPilot keeps home at 0)
 * @param frame        its MAV_FRAME code
 * @param command      its MAV_CMD code
 * @param current      1 for the current item (upload: ignored)
 * @param autocontinue 1 to go on to the next item when done
 * @param param1       param1 (NAV_WAYPOINT: hold time, s)
 * @param param2       param2 (NAV_WAYPOINT: acceptance radius, m)
 * @param param3       param3
 * @param param4       param4 (yaw, degrees; NaN: unchanged)
 * @param x            latitude · 10^7 (or local x)
 * @param y            longitude · 10^7 (or local y)
 * @param z            altitude, m (above home in a relative frame)
 */
record MissionItem(int seq, int frame, int command, int current, int autocontinue, float param1, float param2, float param3,
                   float param4, int x, int y, float z) {
}
