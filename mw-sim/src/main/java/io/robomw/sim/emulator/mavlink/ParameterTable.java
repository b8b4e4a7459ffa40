package io.robomw.sim.emulator.mavlink;

import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.mavlink.wire.ParamType;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;

/**
 * The parameters the emulated autopilot has: those ground stations and MAVSDK read or set, and
 * those that shape what the emulator does (speeds, radii, timeouts, the take-off altitude), with
 * their names, types and defaults as ArduPilot and PX4 give them. A parameter's value travels as a
 * float: ArduPilot casts an integer to float ("C cast"), PX4 sends its 32 bits as they are
 * ("bytewise"), and AUTOPILOT_VERSION says which.
 *
 * <p>Not thread-safe: the simulation's thread.
 */
final class ParameterTable {

    /** One parameter. */
    static final class Parameter {
        final String name;
        final ParamType type;
        double value;

        Parameter(String name, ParamType type, double value) {
            this.name = name;
            this.type = type;
            this.value = value;
        }
    }

    private final Dialect dialect;
    private final Map<String, Parameter> byName = new LinkedHashMap<>();
    private final List<Parameter> byIndex = new ArrayList<>();

    /**
     * @param dialect the autopilot
     * @param drive   the vehicle's limits
     */
    ParameterTable(Dialect dialect, VehicleDrive drive) {
        this.dialect = dialect;
        boolean air = drive.medium() == VehicleDrive.Medium.AIR;
        if (dialect == Dialect.ARDUPILOT) {
            add("SYSID_THISMAV", ParamType.INT16, 1);
            add("SYSID_MYGCS", ParamType.INT16, 255);
            add("FRAME_CLASS", ParamType.INT8, air ? 1 : drive.medium() == VehicleDrive.Medium.WATER ? 2 : 1);
            add("BRD_SAFETY_DEFLT", ParamType.INT8, 0);
            add("DISARM_DELAY", ParamType.INT8, 10);
            add("GUID_TIMEOUT", ParamType.REAL32, 3);
            if (air) {
                add("WPNAV_SPEED", ParamType.REAL32, drive.maxSpeed() * 100);
                add("WPNAV_SPEED_UP", ParamType.REAL32, drive.maxClimbRate() * 100);
                add("WPNAV_SPEED_DN", ParamType.REAL32, drive.maxClimbRate() * 100);
                add("WPNAV_RADIUS", ParamType.REAL32, 100);
                add("LAND_SPEED", ParamType.INT16, 50);
                add("RTL_ALT", ParamType.INT16, 1500);
            } else {
                add("WP_SPEED", ParamType.REAL32, drive.maxSpeed());
                add("WP_RADIUS", ParamType.REAL32, 2);
                add("LOIT_RADIUS", ParamType.REAL32, 2);
            }
        } else {
            add("MAV_SYS_ID", ParamType.INT32, 1);
            add("MAV_TYPE", ParamType.INT32, air ? 2 : drive.medium() == VehicleDrive.Medium.WATER ? 11 : 10);
            add("COM_OF_LOSS_T", ParamType.REAL32, 1.0);
            add("COM_OBL_RC_ACT", ParamType.INT32, 0);
            add("COM_DISARM_PRFLT", ParamType.REAL32, 10);
            add("NAV_ACC_RAD", ParamType.REAL32, 2);
            if (air) {
                add("MIS_TAKEOFF_ALT", ParamType.REAL32, 2.5);
                add("MPC_XY_CRUISE", ParamType.REAL32, drive.maxSpeed());
                add("MPC_Z_VEL_MAX_UP", ParamType.REAL32, drive.maxClimbRate());
                add("MPC_LAND_SPEED", ParamType.REAL32, 0.7);
                add("RTL_RETURN_ALT", ParamType.REAL32, 15);
            } else {
                add("GND_SPEED_MAX", ParamType.REAL32, drive.maxSpeed());
            }
        }
    }

    private void add(String name, ParamType type, double value) {
        Parameter p = new Parameter(name, type, value);
        byName.put(name, p);
        byIndex.add(p);
    }

    /** @return how many there are */
    int count() {
        return byIndex.size();
    }

    /**
     * @param index a parameter's index
     * @return it, if there is one
     */
    Optional<Parameter> at(int index) {
        return index >= 0 && index < byIndex.size() ? Optional.of(byIndex.get(index)) : Optional.empty();
    }

    /**
     * @param name a name
     * @return the parameter, if there is one
     */
    Optional<Parameter> named(String name) {
        return Optional.ofNullable(byName.get(name));
    }

    /** @return a parameter's index */
    int indexOf(Parameter p) {
        return byIndex.indexOf(p);
    }

    /**
     * @param name a parameter's name
     * @return its value
     * @throws IllegalArgumentException if there is none of that name (a bug here)
     */
    double value(String name) {
        Parameter p = byName.get(name);
        if (p == null) {
            throw new IllegalArgumentException("the emulated " + dialect + " has no parameter " + name);
        }
        return p.value;
    }

    /**
     * @param p a parameter
     * @return its value as PARAM_VALUE's float carries it in this dialect
     */
    float encode(Parameter p) {
        if (dialect == Dialect.PX4 && p.type != ParamType.REAL32) {
            return Float.intBitsToFloat((int) p.value);
        }
        return (float) p.value;
    }

    /**
     * @param p    a parameter
     * @param wire a value as PARAM_SET's float carries it in this dialect
     * @return the value
     */
    double decode(Parameter p, float wire) {
        if (dialect == Dialect.PX4 && p.type != ParamType.REAL32) {
            return Float.floatToRawIntBits(wire);
        }
        return p.type == ParamType.REAL32 ? wire : Math.rint(wire);
    }
}
