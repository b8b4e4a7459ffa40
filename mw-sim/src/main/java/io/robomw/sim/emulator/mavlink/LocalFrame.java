package io.robomw.sim.emulator.mavlink;

import io.robomw.sim.world.WorldDescription;

/**
 * The emulated vehicle's frames and the world's. The world: x east, y north, z up, headings
 * anti-clockwise from east. MAVLink's local frame: north-east-down from the vehicle's EKF origin
 * (where it started, on the ground), yaw clockwise from north. Geographic positions come from the
 * world's {@code home} (its origin's latitude, longitude and altitude) on a flat Earth of radius
 * 6,378,137 m (WGS-84's equator), exact enough over a few kilometres. Immutable.
 *
 * @param origin where the world's origin is on Earth
 * @param x0     the vehicle's local origin in the world, x
 * @param y0     its y
 */
record LocalFrame(WorldDescription.GeoOrigin origin, double x0, double y0) {

    /** The Earth's radius used, metres. */
    static final double EARTH_RADIUS = 6_378_137;

    /** @return metres north of the local origin of a world point's y */
    double north(double y) {
        return y - y0;
    }

    /** @return metres east of the local origin of a world point's x */
    double east(double x) {
        return x - x0;
    }

    /** @return the world x of a local east */
    double worldX(double east) {
        return x0 + east;
    }

    /** @return the world y of a local north */
    double worldY(double north) {
        return y0 + north;
    }

    /**
     * @param heading a world heading, radians anti-clockwise from east
     * @return the MAVLink yaw, radians clockwise from north, in (-π, π]
     */
    static double yaw(double heading) {
        return normalize(Math.PI / 2 - heading);
    }

    /**
     * @param yaw a MAVLink yaw, clockwise from north
     * @return the world heading, anti-clockwise from east
     */
    static double heading(double yaw) {
        return normalize(Math.PI / 2 - yaw);
    }

    /** @return an angle in (-π, π] */
    static double normalize(double a) {
        double r = Math.IEEEremainder(a, 2 * Math.PI);
        return r <= -Math.PI ? r + 2 * Math.PI : r;
    }

    /** @return the latitude of a world y, degrees */
    double latitude(double y) {
        return origin.latitude() + Math.toDegrees(y / EARTH_RADIUS);
    }

    /** @return the longitude of a world x, degrees */
    double longitude(double x) {
        return origin.longitude() + Math.toDegrees(x / (EARTH_RADIUS * Math.cos(Math.toRadians(origin.latitude()))));
    }

    /** @return the world y of a latitude */
    double worldYOf(double latitude) {
        return Math.toRadians(latitude - origin.latitude()) * EARTH_RADIUS;
    }

    /** @return the world x of a longitude */
    double worldXOf(double longitude) {
        return Math.toRadians(longitude - origin.longitude()) * EARTH_RADIUS * Math.cos(Math.toRadians(origin.latitude()));
    }

    /** @return metres above mean sea level of a world altitude */
    double amsl(double z) {
        return origin.altitude() + z;
    }
}
