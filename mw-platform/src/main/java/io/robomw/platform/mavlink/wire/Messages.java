package io.robomw.platform.mavlink.wire;

import java.util.List;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;

/**
 * The messages RoboMW's MAVLink driver and emulator use, each with its id, CRC_EXTRA and fields as
 * the MAVLink definitions give them ({@code minimal.xml}, {@code standard.xml} and
 * {@code common.xml} as shipped with pymavlink 2.4.50; field descriptions shortened to their first
 * sentence, units in brackets). Any other message id is unknown to the decoder and passes by
 * ({@link FrameDecoder}). The CRC_EXTRA written here is checked against the one computed from the
 * fields ({@link MessageType#computedCrcExtra}) by the tests, so a field typed or ordered wrongly
 * here cannot go unnoticed.
 *
 * <p>How this file was made: each message's {@code <message>} element was read from those XML files
 * (fields in declared order, {@code <extensions/>} kept) and its CRC_EXTRA from pymavlink's
 * generated {@code common.py}; the classes were written from them and then checked by hand against
 * mavlink.io/en/messages/common.html.
 */
public final class Messages {

    private Messages() {
    }

    /** Every message of this dialect. */
    public static final List<MessageType> ALL = List.of(
            Heartbeat.MESSAGE,
            SysStatus.MESSAGE,
            SystemTime.MESSAGE,
            Ping.MESSAGE,
            SetMode.MESSAGE,
            ParamRequestRead.MESSAGE,
            ParamRequestList.MESSAGE,
            ParamValue.MESSAGE,
            ParamSet.MESSAGE,
            GpsRawInt.MESSAGE,
            Attitude.MESSAGE,
            LocalPositionNed.MESSAGE,
            GlobalPositionInt.MESSAGE,
            MissionRequest.MESSAGE,
            MissionSetCurrent.MESSAGE,
            MissionCurrent.MESSAGE,
            MissionRequestList.MESSAGE,
            MissionCount.MESSAGE,
            MissionClearAll.MESSAGE,
            MissionItemReached.MESSAGE,
            MissionAck.MESSAGE,
            MissionRequestInt.MESSAGE,
            ManualControl.MESSAGE,
            MissionItemInt.MESSAGE,
            VfrHud.MESSAGE,
            CommandInt.MESSAGE,
            CommandLong.MESSAGE,
            CommandAck.MESSAGE,
            SetAttitudeTarget.MESSAGE,
            SetPositionTargetLocalNed.MESSAGE,
            PositionTargetLocalNed.MESSAGE,
            SetPositionTargetGlobalInt.MESSAGE,
            RadioStatus.MESSAGE,
            Timesync.MESSAGE,
            DistanceSensor.MESSAGE,
            BatteryStatus.MESSAGE,
            AutopilotVersion.MESSAGE,
            HomePosition.MESSAGE,
            ExtendedSysState.MESSAGE,
            Statustext.MESSAGE,
            SetupSigning.MESSAGE);

    private static final Map<Integer, MessageType> BY_ID = ALL.stream()
            .collect(Collectors.toUnmodifiableMap(MessageType::id, Function.identity()));

    /**
     * @param id a message id
     * @return its message type, or {@code null} when this dialect does not know it
     */
    public static MessageType byId(int id) {
        return BY_ID.get(id);
    }

    /** HEARTBEAT (0): The heartbeat message shows that a system or component is present and responding. */
    public static final class Heartbeat {
        /** The message: id 0, CRC_EXTRA 50, at most 9 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("HEARTBEAT", 0, 50, "uint8_t type", "uint8_t autopilot",
                "uint8_t base_mode", "uint32_t custom_mode", "uint8_t system_status", "uint8_t mavlink_version");
        /** Vehicle or component type. */
        public static final Field TYPE = MESSAGE.field("type");
        /** Autopilot type / class. */
        public static final Field AUTOPILOT = MESSAGE.field("autopilot");
        /** System mode bitmap. */
        public static final Field BASE_MODE = MESSAGE.field("base_mode");
        /** A bitfield for use for autopilot-specific flags */
        public static final Field CUSTOM_MODE = MESSAGE.field("custom_mode");
        /** System status flag. */
        public static final Field SYSTEM_STATUS = MESSAGE.field("system_status");
        /** MAVLink version, not writable by user, gets added by protocol because of magic data type: uint8_t_mavlink_version */
        public static final Field MAVLINK_VERSION = MESSAGE.field("mavlink_version");

        private Heartbeat() {
        }
    }

    /** SYS_STATUS (1): Sensor and subsystem status information. */
    public static final class SysStatus {
        /** The message: id 1, CRC_EXTRA 124, at most 43 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("SYS_STATUS", 1, 124,
                "uint32_t onboard_control_sensors_present", "uint32_t onboard_control_sensors_enabled",
                "uint32_t onboard_control_sensors_health", "uint16_t load", "uint16_t voltage_battery", "int16_t current_battery",
                "int8_t battery_remaining", "uint16_t drop_rate_comm", "uint16_t errors_comm", "uint16_t errors_count1",
                "uint16_t errors_count2", "uint16_t errors_count3", "uint16_t errors_count4", MessageType.EXTENSIONS,
                "uint32_t onboard_control_sensors_present_extended", "uint32_t onboard_control_sensors_enabled_extended",
                "uint32_t onboard_control_sensors_health_extended");
        /** Bitmap showing which onboard controllers and sensors are present. */
        public static final Field ONBOARD_CONTROL_SENSORS_PRESENT = MESSAGE.field("onboard_control_sensors_present");
        /** Bitmap showing which onboard controllers and sensors are enabled: Value of 0: not enabled. */
        public static final Field ONBOARD_CONTROL_SENSORS_ENABLED = MESSAGE.field("onboard_control_sensors_enabled");
        /** Bitmap showing which onboard controllers and sensors have an error (or are operational). */
        public static final Field ONBOARD_CONTROL_SENSORS_HEALTH = MESSAGE.field("onboard_control_sensors_health");
        /** Maximum usage in percent of the mainloop time. [d%] */
        public static final Field LOAD = MESSAGE.field("load");
        /** Battery voltage, UINT16_MAX: Voltage not sent by autopilot. [mV] */
        public static final Field VOLTAGE_BATTERY = MESSAGE.field("voltage_battery");
        /** Battery current, -1: Current not sent by autopilot. [cA] */
        public static final Field CURRENT_BATTERY = MESSAGE.field("current_battery");
        /** Battery energy remaining, -1: Battery remaining energy not sent by autopilot. [%] */
        public static final Field BATTERY_REMAINING = MESSAGE.field("battery_remaining");
        /** Communication drop rate, (UART, I2C, SPI, CAN), dropped packets on all links (packets that were corrupted on reception on the MAV) [c%] */
        public static final Field DROP_RATE_COMM = MESSAGE.field("drop_rate_comm");
        /** Communication errors (UART, I2C, SPI, CAN), dropped packets on all links (packets that were corrupted on reception on the MAV) */
        public static final Field ERRORS_COMM = MESSAGE.field("errors_comm");
        /** Autopilot-specific errors */
        public static final Field ERRORS_COUNT1 = MESSAGE.field("errors_count1");
        /** Autopilot-specific errors */
        public static final Field ERRORS_COUNT2 = MESSAGE.field("errors_count2");
        /** Autopilot-specific errors */
        public static final Field ERRORS_COUNT3 = MESSAGE.field("errors_count3");
        /** Autopilot-specific errors */
        public static final Field ERRORS_COUNT4 = MESSAGE.field("errors_count4");
        /** Bitmap showing which onboard controllers and sensors are present. */
        public static final Field ONBOARD_CONTROL_SENSORS_PRESENT_EXTENDED = MESSAGE.field("onboard_control_sensors_present_extended");
        /** Bitmap showing which onboard controllers and sensors are enabled: Value of 0: not enabled. */
        public static final Field ONBOARD_CONTROL_SENSORS_ENABLED_EXTENDED = MESSAGE.field("onboard_control_sensors_enabled_extended");
        /** Bitmap showing which onboard controllers and sensors have an error (or are operational). */
        public static final Field ONBOARD_CONTROL_SENSORS_HEALTH_EXTENDED = MESSAGE.field("onboard_control_sensors_health_extended");

        private SysStatus() {
        }
    }

    /** SYSTEM_TIME (2): The system time is the time of the sender's master clock. */
    public static final class SystemTime {
        /** The message: id 2, CRC_EXTRA 137, at most 12 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("SYSTEM_TIME", 2, 137, "uint64_t time_unix_usec",
                "uint32_t time_boot_ms");
        /** Timestamp (UNIX epoch time). [us] */
        public static final Field TIME_UNIX_USEC = MESSAGE.field("time_unix_usec");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");

        private SystemTime() {
        }
    }

    /** PING (4): A ping message either requesting or responding to a ping. */
    public static final class Ping {
        /** The message: id 4, CRC_EXTRA 237, at most 14 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("PING", 4, 237, "uint64_t time_usec", "uint32_t seq",
                "uint8_t target_system", "uint8_t target_component");
        /** Timestamp (UNIX Epoch time or time since system boot). [us] */
        public static final Field TIME_USEC = MESSAGE.field("time_usec");
        /** PING sequence */
        public static final Field SEQ = MESSAGE.field("seq");
        /** 0: request ping from all receiving systems. */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** 0: request ping from all receiving components. */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");

        private Ping() {
        }
    }

    /** SET_MODE (11): Set the system mode, as defined by enum MAV_MODE. */
    public static final class SetMode {
        /** The message: id 11, CRC_EXTRA 89, at most 6 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("SET_MODE", 11, 89, "uint8_t target_system",
                "uint8_t base_mode", "uint32_t custom_mode");
        /** The system setting the mode */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** The new base mode. */
        public static final Field BASE_MODE = MESSAGE.field("base_mode");
        /** The new autopilot-specific mode. */
        public static final Field CUSTOM_MODE = MESSAGE.field("custom_mode");

        private SetMode() {
        }
    }

    /** PARAM_REQUEST_READ (20): Request to read the onboard parameter with the param_id string id. */
    public static final class ParamRequestRead {
        /** The message: id 20, CRC_EXTRA 214, at most 20 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("PARAM_REQUEST_READ", 20, 214, "uint8_t target_system",
                "uint8_t target_component", "char[16] param_id", "int16_t param_index");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Onboard parameter id, terminated by NULL if the length is less than 16 human-readable chars and WITHOUT null termination (NULL) byte if the length is exactly... */
        public static final Field PARAM_ID = MESSAGE.field("param_id");
        /** Parameter index. */
        public static final Field PARAM_INDEX = MESSAGE.field("param_index");

        private ParamRequestRead() {
        }
    }

    /** PARAM_REQUEST_LIST (21): Request all parameters of this component. */
    public static final class ParamRequestList {
        /** The message: id 21, CRC_EXTRA 159, at most 2 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("PARAM_REQUEST_LIST", 21, 159, "uint8_t target_system",
                "uint8_t target_component");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");

        private ParamRequestList() {
        }
    }

    /** PARAM_VALUE (22): Emit the value of a onboard parameter. */
    public static final class ParamValue {
        /** The message: id 22, CRC_EXTRA 220, at most 25 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("PARAM_VALUE", 22, 220, "char[16] param_id",
                "float param_value", "uint8_t param_type", "uint16_t param_count", "uint16_t param_index");
        /** Onboard parameter id, terminated by NULL if the length is less than 16 human-readable chars and WITHOUT null termination (NULL) byte if the length is exactly... */
        public static final Field PARAM_ID = MESSAGE.field("param_id");
        /** Onboard parameter value */
        public static final Field PARAM_VALUE = MESSAGE.field("param_value");
        /** Onboard parameter type. */
        public static final Field PARAM_TYPE = MESSAGE.field("param_type");
        /** Total number of onboard parameters */
        public static final Field PARAM_COUNT = MESSAGE.field("param_count");
        /** Index of this onboard parameter */
        public static final Field PARAM_INDEX = MESSAGE.field("param_index");

        private ParamValue() {
        }
    }

    /** PARAM_SET (23): Set a parameter value (write new value to permanent storage). */
    public static final class ParamSet {
        /** The message: id 23, CRC_EXTRA 168, at most 23 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("PARAM_SET", 23, 168, "uint8_t target_system",
                "uint8_t target_component", "char[16] param_id", "float param_value", "uint8_t param_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Onboard parameter id, terminated by NULL if the length is less than 16 human-readable chars and WITHOUT null termination (NULL) byte if the length is exactly... */
        public static final Field PARAM_ID = MESSAGE.field("param_id");
        /** Onboard parameter value */
        public static final Field PARAM_VALUE = MESSAGE.field("param_value");
        /** Onboard parameter type. */
        public static final Field PARAM_TYPE = MESSAGE.field("param_type");

        private ParamSet() {
        }
    }

    /** GPS_RAW_INT (24): The global position, as returned by the Global Positioning System (GPS). */
    public static final class GpsRawInt {
        /** The message: id 24, CRC_EXTRA 24, at most 52 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("GPS_RAW_INT", 24, 24, "uint64_t time_usec",
                "uint8_t fix_type", "int32_t lat", "int32_t lon", "int32_t alt", "uint16_t eph", "uint16_t epv", "uint16_t vel",
                "uint16_t cog", "uint8_t satellites_visible", MessageType.EXTENSIONS, "int32_t alt_ellipsoid", "uint32_t h_acc",
                "uint32_t v_acc", "uint32_t vel_acc", "uint32_t hdg_acc", "uint16_t yaw");
        /** Timestamp (UNIX Epoch time or time since system boot). [us] */
        public static final Field TIME_USEC = MESSAGE.field("time_usec");
        /** GPS fix type. */
        public static final Field FIX_TYPE = MESSAGE.field("fix_type");
        /** Latitude (WGS84, EGM96 ellipsoid) [degE7] */
        public static final Field LAT = MESSAGE.field("lat");
        /** Longitude (WGS84, EGM96 ellipsoid) [degE7] */
        public static final Field LON = MESSAGE.field("lon");
        /** Altitude (MSL). [mm] */
        public static final Field ALT = MESSAGE.field("alt");
        /** GPS HDOP horizontal dilution of position (unitless * 100). */
        public static final Field EPH = MESSAGE.field("eph");
        /** GPS VDOP vertical dilution of position (unitless * 100). */
        public static final Field EPV = MESSAGE.field("epv");
        /** GPS ground speed. [cm/s] */
        public static final Field VEL = MESSAGE.field("vel");
        /** Course over ground (NOT heading, but direction of movement) in degrees * 100, 0.0..359.99 degrees. [cdeg] */
        public static final Field COG = MESSAGE.field("cog");
        /** Number of satellites visible. */
        public static final Field SATELLITES_VISIBLE = MESSAGE.field("satellites_visible");
        /** Altitude (above WGS84, EGM96 ellipsoid). [mm] */
        public static final Field ALT_ELLIPSOID = MESSAGE.field("alt_ellipsoid");
        /** Position uncertainty. [mm] */
        public static final Field H_ACC = MESSAGE.field("h_acc");
        /** Altitude uncertainty. [mm] */
        public static final Field V_ACC = MESSAGE.field("v_acc");
        /** Speed uncertainty. [mm/s] */
        public static final Field VEL_ACC = MESSAGE.field("vel_acc");
        /** Heading / track uncertainty [degE5] */
        public static final Field HDG_ACC = MESSAGE.field("hdg_acc");
        /** Yaw in earth frame from north. [cdeg] */
        public static final Field YAW = MESSAGE.field("yaw");

        private GpsRawInt() {
        }
    }

    /** ATTITUDE (30): The attitude in the aeronautical frame (right-handed, Z-down, Y-right, X-front, ZYX, intrinsic). */
    public static final class Attitude {
        /** The message: id 30, CRC_EXTRA 39, at most 28 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("ATTITUDE", 30, 39, "uint32_t time_boot_ms", "float roll",
                "float pitch", "float yaw", "float rollspeed", "float pitchspeed", "float yawspeed");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** Roll angle (-pi..+pi) [rad] */
        public static final Field ROLL = MESSAGE.field("roll");
        /** Pitch angle (-pi..+pi) [rad] */
        public static final Field PITCH = MESSAGE.field("pitch");
        /** Yaw angle (-pi..+pi) [rad] */
        public static final Field YAW = MESSAGE.field("yaw");
        /** Roll angular speed [rad/s] */
        public static final Field ROLLSPEED = MESSAGE.field("rollspeed");
        /** Pitch angular speed [rad/s] */
        public static final Field PITCHSPEED = MESSAGE.field("pitchspeed");
        /** Yaw angular speed [rad/s] */
        public static final Field YAWSPEED = MESSAGE.field("yawspeed");

        private Attitude() {
        }
    }

    /** LOCAL_POSITION_NED (32): The filtered local position (e.g. */
    public static final class LocalPositionNed {
        /** The message: id 32, CRC_EXTRA 185, at most 28 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("LOCAL_POSITION_NED", 32, 185, "uint32_t time_boot_ms",
                "float x", "float y", "float z", "float vx", "float vy", "float vz");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** X Position [m] */
        public static final Field X = MESSAGE.field("x");
        /** Y Position [m] */
        public static final Field Y = MESSAGE.field("y");
        /** Z Position [m] */
        public static final Field Z = MESSAGE.field("z");
        /** X Speed [m/s] */
        public static final Field VX = MESSAGE.field("vx");
        /** Y Speed [m/s] */
        public static final Field VY = MESSAGE.field("vy");
        /** Z Speed [m/s] */
        public static final Field VZ = MESSAGE.field("vz");

        private LocalPositionNed() {
        }
    }

    /** GLOBAL_POSITION_INT (33): The filtered global position (e.g. */
    public static final class GlobalPositionInt {
        /** The message: id 33, CRC_EXTRA 104, at most 28 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("GLOBAL_POSITION_INT", 33, 104, "uint32_t time_boot_ms",
                "int32_t lat", "int32_t lon", "int32_t alt", "int32_t relative_alt", "int16_t vx", "int16_t vy", "int16_t vz",
                "uint16_t hdg");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** Latitude, expressed [degE7] */
        public static final Field LAT = MESSAGE.field("lat");
        /** Longitude, expressed [degE7] */
        public static final Field LON = MESSAGE.field("lon");
        /** Altitude (MSL). [mm] */
        public static final Field ALT = MESSAGE.field("alt");
        /** Altitude above home [mm] */
        public static final Field RELATIVE_ALT = MESSAGE.field("relative_alt");
        /** Ground X Speed (Latitude, positive north) [cm/s] */
        public static final Field VX = MESSAGE.field("vx");
        /** Ground Y Speed (Longitude, positive east) [cm/s] */
        public static final Field VY = MESSAGE.field("vy");
        /** Ground Z Speed (Altitude, positive down) [cm/s] */
        public static final Field VZ = MESSAGE.field("vz");
        /** Vehicle heading (yaw angle), 0.0..359.99 degrees. [cdeg] */
        public static final Field HDG = MESSAGE.field("hdg");

        private GlobalPositionInt() {
        }
    }

    /** MISSION_REQUEST (40): Request the information of the mission item with the sequence number seq. */
    public static final class MissionRequest {
        /** The message: id 40, CRC_EXTRA 230, at most 5 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_REQUEST", 40, 230, "uint8_t target_system",
                "uint8_t target_component", "uint16_t seq", MessageType.EXTENSIONS, "uint8_t mission_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Sequence */
        public static final Field SEQ = MESSAGE.field("seq");
        /** Mission type. */
        public static final Field MISSION_TYPE = MESSAGE.field("mission_type");

        private MissionRequest() {
        }
    }

    /** MISSION_SET_CURRENT (41): Set the mission item with sequence number seq as the current item and emit MISSION_CURRENT (whether or not the mission number changed). */
    public static final class MissionSetCurrent {
        /** The message: id 41, CRC_EXTRA 28, at most 4 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_SET_CURRENT", 41, 28, "uint8_t target_system",
                "uint8_t target_component", "uint16_t seq");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Sequence */
        public static final Field SEQ = MESSAGE.field("seq");

        private MissionSetCurrent() {
        }
    }

    /** MISSION_CURRENT (42): Message that announces the sequence number of the current target mission item (that the system will fly towards/execute when the mission is running). */
    public static final class MissionCurrent {
        /** The message: id 42, CRC_EXTRA 28, at most 6 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_CURRENT", 42, 28, "uint16_t seq",
                MessageType.EXTENSIONS, "uint16_t total", "uint8_t mission_state", "uint8_t mission_mode");
        /** Sequence */
        public static final Field SEQ = MESSAGE.field("seq");
        /** Total number of mission items on vehicle (on last item, sequence == total). */
        public static final Field TOTAL = MESSAGE.field("total");
        /** Mission state machine state. */
        public static final Field MISSION_STATE = MESSAGE.field("mission_state");
        /** Vehicle is in a mode that can execute mission items or suspended. */
        public static final Field MISSION_MODE = MESSAGE.field("mission_mode");

        private MissionCurrent() {
        }
    }

    /** MISSION_REQUEST_LIST (43): Request the overall list of mission items from the system/component. */
    public static final class MissionRequestList {
        /** The message: id 43, CRC_EXTRA 132, at most 3 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_REQUEST_LIST", 43, 132, "uint8_t target_system",
                "uint8_t target_component", MessageType.EXTENSIONS, "uint8_t mission_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Mission type. */
        public static final Field MISSION_TYPE = MESSAGE.field("mission_type");

        private MissionRequestList() {
        }
    }

    /** MISSION_COUNT (44): This message is emitted as response to MISSION_REQUEST_LIST by the MAV and to initiate a write transaction. */
    public static final class MissionCount {
        /** The message: id 44, CRC_EXTRA 221, at most 5 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_COUNT", 44, 221, "uint8_t target_system",
                "uint8_t target_component", "uint16_t count", MessageType.EXTENSIONS, "uint8_t mission_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Number of mission items in the sequence */
        public static final Field COUNT = MESSAGE.field("count");
        /** Mission type. */
        public static final Field MISSION_TYPE = MESSAGE.field("mission_type");

        private MissionCount() {
        }
    }

    /** MISSION_CLEAR_ALL (45): Delete all mission items at once. */
    public static final class MissionClearAll {
        /** The message: id 45, CRC_EXTRA 232, at most 3 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_CLEAR_ALL", 45, 232, "uint8_t target_system",
                "uint8_t target_component", MessageType.EXTENSIONS, "uint8_t mission_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Mission type. */
        public static final Field MISSION_TYPE = MESSAGE.field("mission_type");

        private MissionClearAll() {
        }
    }

    /** MISSION_ITEM_REACHED (46): A certain mission item has been reached. */
    public static final class MissionItemReached {
        /** The message: id 46, CRC_EXTRA 11, at most 2 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_ITEM_REACHED", 46, 11, "uint16_t seq");
        /** Sequence */
        public static final Field SEQ = MESSAGE.field("seq");

        private MissionItemReached() {
        }
    }

    /** MISSION_ACK (47): Acknowledgment message during waypoint handling. */
    public static final class MissionAck {
        /** The message: id 47, CRC_EXTRA 153, at most 4 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_ACK", 47, 153, "uint8_t target_system",
                "uint8_t target_component", "uint8_t type", MessageType.EXTENSIONS, "uint8_t mission_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Mission result. */
        public static final Field TYPE = MESSAGE.field("type");
        /** Mission type. */
        public static final Field MISSION_TYPE = MESSAGE.field("mission_type");

        private MissionAck() {
        }
    }

    /** MISSION_REQUEST_INT (51): Request the information of the mission item with the sequence number seq. */
    public static final class MissionRequestInt {
        /** The message: id 51, CRC_EXTRA 196, at most 5 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_REQUEST_INT", 51, 196, "uint8_t target_system",
                "uint8_t target_component", "uint16_t seq", MessageType.EXTENSIONS, "uint8_t mission_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Sequence */
        public static final Field SEQ = MESSAGE.field("seq");
        /** Mission type. */
        public static final Field MISSION_TYPE = MESSAGE.field("mission_type");

        private MissionRequestInt() {
        }
    }

    /** MANUAL_CONTROL (69): This message provides an API for manually controlling the vehicle using standard joystick axes nomenclature, along with a joystick-like input device. */
    public static final class ManualControl {
        /** The message: id 69, CRC_EXTRA 243, at most 30 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MANUAL_CONTROL", 69, 243, "uint8_t target", "int16_t x",
                "int16_t y", "int16_t z", "int16_t r", "uint16_t buttons", MessageType.EXTENSIONS, "uint16_t buttons2",
                "uint8_t enabled_extensions", "int16_t s", "int16_t t", "int16_t aux1", "int16_t aux2", "int16_t aux3",
                "int16_t aux4", "int16_t aux5", "int16_t aux6");
        /** The system to be controlled. */
        public static final Field TARGET = MESSAGE.field("target");
        /** X-axis, normalized to the range [-1000,1000]. */
        public static final Field X = MESSAGE.field("x");
        /** Y-axis, normalized to the range [-1000,1000]. */
        public static final Field Y = MESSAGE.field("y");
        /** Z-axis, normalized to the range [-1000,1000]. */
        public static final Field Z = MESSAGE.field("z");
        /** R-axis, normalized to the range [-1000,1000]. */
        public static final Field R = MESSAGE.field("r");
        /** A bitfield corresponding to the joystick buttons' current state, 1 for pressed, 0 for released. */
        public static final Field BUTTONS = MESSAGE.field("buttons");
        /** A bitfield corresponding to the joystick buttons' 16-31 current state, 1 for pressed, 0 for released. */
        public static final Field BUTTONS2 = MESSAGE.field("buttons2");
        /** Set bits to 1 to indicate which of the following extension fields contain valid data: bit 0: pitch, bit 1: roll, bit 2: aux1, bit 3: aux2, bit 4: aux3, bit 5... */
        public static final Field ENABLED_EXTENSIONS = MESSAGE.field("enabled_extensions");
        /** Pitch-only-axis, normalized to the range [-1000,1000]. */
        public static final Field S = MESSAGE.field("s");
        /** Roll-only-axis, normalized to the range [-1000,1000]. */
        public static final Field T = MESSAGE.field("t");
        /** Aux continuous input field 1. */
        public static final Field AUX1 = MESSAGE.field("aux1");
        /** Aux continuous input field 2. */
        public static final Field AUX2 = MESSAGE.field("aux2");
        /** Aux continuous input field 3. */
        public static final Field AUX3 = MESSAGE.field("aux3");
        /** Aux continuous input field 4. */
        public static final Field AUX4 = MESSAGE.field("aux4");
        /** Aux continuous input field 5. */
        public static final Field AUX5 = MESSAGE.field("aux5");
        /** Aux continuous input field 6. */
        public static final Field AUX6 = MESSAGE.field("aux6");

        private ManualControl() {
        }
    }

    /** MISSION_ITEM_INT (73): Message encoding a mission item. */
    public static final class MissionItemInt {
        /** The message: id 73, CRC_EXTRA 38, at most 38 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("MISSION_ITEM_INT", 73, 38, "uint8_t target_system",
                "uint8_t target_component", "uint16_t seq", "uint8_t frame", "uint16_t command", "uint8_t current",
                "uint8_t autocontinue", "float param1", "float param2", "float param3", "float param4", "int32_t x", "int32_t y",
                "float z", MessageType.EXTENSIONS, "uint8_t mission_type");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Waypoint ID (sequence number). */
        public static final Field SEQ = MESSAGE.field("seq");
        /** The coordinate system of the waypoint. */
        public static final Field FRAME = MESSAGE.field("frame");
        /** The scheduled action for the waypoint. */
        public static final Field COMMAND = MESSAGE.field("command");
        /** false:0, true:1 */
        public static final Field CURRENT = MESSAGE.field("current");
        /** Autocontinue to next waypoint. */
        public static final Field AUTOCONTINUE = MESSAGE.field("autocontinue");
        /** PARAM1, see MAV_CMD enum */
        public static final Field PARAM1 = MESSAGE.field("param1");
        /** PARAM2, see MAV_CMD enum */
        public static final Field PARAM2 = MESSAGE.field("param2");
        /** PARAM3, see MAV_CMD enum */
        public static final Field PARAM3 = MESSAGE.field("param3");
        /** PARAM4, see MAV_CMD enum */
        public static final Field PARAM4 = MESSAGE.field("param4");
        /** PARAM5 / local: x position in meters * 1e4, global: latitude in degrees * 10^7 */
        public static final Field X = MESSAGE.field("x");
        /** PARAM6 / y position: local: x position in meters * 1e4, global: longitude in degrees *10^7 */
        public static final Field Y = MESSAGE.field("y");
        /** PARAM7 / z position: global: altitude in meters (relative or absolute, depending on frame. */
        public static final Field Z = MESSAGE.field("z");
        /** Mission type. */
        public static final Field MISSION_TYPE = MESSAGE.field("mission_type");

        private MissionItemInt() {
        }
    }

    /** VFR_HUD (74): Metrics typically displayed on a HUD for fixed wing aircraft. */
    public static final class VfrHud {
        /** The message: id 74, CRC_EXTRA 20, at most 20 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("VFR_HUD", 74, 20, "float airspeed", "float groundspeed",
                "int16_t heading", "uint16_t throttle", "float alt", "float climb");
        /** Vehicle speed in form appropriate for vehicle type. [m/s] */
        public static final Field AIRSPEED = MESSAGE.field("airspeed");
        /** Current ground speed. [m/s] */
        public static final Field GROUNDSPEED = MESSAGE.field("groundspeed");
        /** Current heading in compass units (0-360, 0=north). [deg] */
        public static final Field HEADING = MESSAGE.field("heading");
        /** Current throttle setting (0 to 100). [%] */
        public static final Field THROTTLE = MESSAGE.field("throttle");
        /** Current altitude (MSL). [m] */
        public static final Field ALT = MESSAGE.field("alt");
        /** Current climb rate. [m/s] */
        public static final Field CLIMB = MESSAGE.field("climb");

        private VfrHud() {
        }
    }

    /** COMMAND_INT (75): Message encoding a command with parameters as scaled integers. */
    public static final class CommandInt {
        /** The message: id 75, CRC_EXTRA 158, at most 35 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("COMMAND_INT", 75, 158, "uint8_t target_system",
                "uint8_t target_component", "uint8_t frame", "uint16_t command", "uint8_t current", "uint8_t autocontinue",
                "float param1", "float param2", "float param3", "float param4", "int32_t x", "int32_t y", "float z");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** The coordinate system of the COMMAND. */
        public static final Field FRAME = MESSAGE.field("frame");
        /** The scheduled action for the mission item. */
        public static final Field COMMAND = MESSAGE.field("command");
        /** Not used. */
        public static final Field CURRENT = MESSAGE.field("current");
        /** Not used (set 0). */
        public static final Field AUTOCONTINUE = MESSAGE.field("autocontinue");
        /** PARAM1, see MAV_CMD enum */
        public static final Field PARAM1 = MESSAGE.field("param1");
        /** PARAM2, see MAV_CMD enum */
        public static final Field PARAM2 = MESSAGE.field("param2");
        /** PARAM3, see MAV_CMD enum */
        public static final Field PARAM3 = MESSAGE.field("param3");
        /** PARAM4, see MAV_CMD enum */
        public static final Field PARAM4 = MESSAGE.field("param4");
        /** PARAM5 / local: x position in meters * 1e4, global: latitude in degrees * 10^7 */
        public static final Field X = MESSAGE.field("x");
        /** PARAM6 / local: y position in meters * 1e4, global: longitude in degrees * 10^7 */
        public static final Field Y = MESSAGE.field("y");
        /** PARAM7 / z position: global: altitude in meters (relative or absolute, depending on frame). */
        public static final Field Z = MESSAGE.field("z");

        private CommandInt() {
        }
    }

    /** COMMAND_LONG (76): Send a command with up to seven parameters to the MAV. */
    public static final class CommandLong {
        /** The message: id 76, CRC_EXTRA 152, at most 33 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("COMMAND_LONG", 76, 152, "uint8_t target_system",
                "uint8_t target_component", "uint16_t command", "uint8_t confirmation", "float param1", "float param2",
                "float param3", "float param4", "float param5", "float param6", "float param7");
        /** System which should execute the command */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component which should execute the command, 0 for all components */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Command ID (of command to send). */
        public static final Field COMMAND = MESSAGE.field("command");
        /** 0: First transmission of this command. */
        public static final Field CONFIRMATION = MESSAGE.field("confirmation");
        /** Parameter 1 (for the specific command). */
        public static final Field PARAM1 = MESSAGE.field("param1");
        /** Parameter 2 (for the specific command). */
        public static final Field PARAM2 = MESSAGE.field("param2");
        /** Parameter 3 (for the specific command). */
        public static final Field PARAM3 = MESSAGE.field("param3");
        /** Parameter 4 (for the specific command). */
        public static final Field PARAM4 = MESSAGE.field("param4");
        /** Parameter 5 (for the specific command). */
        public static final Field PARAM5 = MESSAGE.field("param5");
        /** Parameter 6 (for the specific command). */
        public static final Field PARAM6 = MESSAGE.field("param6");
        /** Parameter 7 (for the specific command). */
        public static final Field PARAM7 = MESSAGE.field("param7");

        private CommandLong() {
        }
    }

    /** COMMAND_ACK (77): Report status of a command. */
    public static final class CommandAck {
        /** The message: id 77, CRC_EXTRA 143, at most 10 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("COMMAND_ACK", 77, 143, "uint16_t command", "uint8_t result",
                MessageType.EXTENSIONS, "uint8_t progress", "int32_t result_param2", "uint8_t target_system",
                "uint8_t target_component");
        /** Command ID (of acknowledged command). */
        public static final Field COMMAND = MESSAGE.field("command");
        /** Result of command. */
        public static final Field RESULT = MESSAGE.field("result");
        /** Also used as result_param1, it can be set with a enum containing the errors reasons of why the command was denied or the progress percentage or 255 if unknow... */
        public static final Field PROGRESS = MESSAGE.field("progress");
        /** Additional parameter of the result, example: which parameter of MAV_CMD_NAV_WAYPOINT caused it to be denied. */
        public static final Field RESULT_PARAM2 = MESSAGE.field("result_param2");
        /** System which requested the command to be executed */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component which requested the command to be executed */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");

        private CommandAck() {
        }
    }

    /** SET_ATTITUDE_TARGET (82): Sets a desired vehicle attitude. */
    public static final class SetAttitudeTarget {
        /** The message: id 82, CRC_EXTRA 49, at most 39 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("SET_ATTITUDE_TARGET", 82, 49, "uint32_t time_boot_ms",
                "uint8_t target_system", "uint8_t target_component", "uint8_t type_mask", "float[4] q", "float body_roll_rate",
                "float body_pitch_rate", "float body_yaw_rate", "float thrust");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Bitmap to indicate which dimensions should be ignored by the vehicle. */
        public static final Field TYPE_MASK = MESSAGE.field("type_mask");
        /** Attitude quaternion (w, x, y, z order, zero-rotation is 1, 0, 0, 0) */
        public static final Field Q = MESSAGE.field("q");
        /** Body roll rate [rad/s] */
        public static final Field BODY_ROLL_RATE = MESSAGE.field("body_roll_rate");
        /** Body pitch rate [rad/s] */
        public static final Field BODY_PITCH_RATE = MESSAGE.field("body_pitch_rate");
        /** Body yaw rate [rad/s] */
        public static final Field BODY_YAW_RATE = MESSAGE.field("body_yaw_rate");
        /** Collective thrust, normalized to 0 .. */
        public static final Field THRUST = MESSAGE.field("thrust");

        private SetAttitudeTarget() {
        }
    }

    /** SET_POSITION_TARGET_LOCAL_NED (84): Sets a desired vehicle position in a local north-east-down coordinate frame. */
    public static final class SetPositionTargetLocalNed {
        /** The message: id 84, CRC_EXTRA 143, at most 53 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("SET_POSITION_TARGET_LOCAL_NED", 84, 143,
                "uint32_t time_boot_ms", "uint8_t target_system", "uint8_t target_component", "uint8_t coordinate_frame",
                "uint16_t type_mask", "float x", "float y", "float z", "float vx", "float vy", "float vz", "float afx",
                "float afy", "float afz", "float yaw", "float yaw_rate");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Valid options are: MAV_FRAME_LOCAL_NED = 1, MAV_FRAME_LOCAL_OFFSET_NED = 7, MAV_FRAME_BODY_NED = 8, MAV_FRAME_BODY_OFFSET_NED = 9 */
        public static final Field COORDINATE_FRAME = MESSAGE.field("coordinate_frame");
        /** Bitmap to indicate which dimensions should be ignored by the vehicle. */
        public static final Field TYPE_MASK = MESSAGE.field("type_mask");
        /** X Position in NED frame [m] */
        public static final Field X = MESSAGE.field("x");
        /** Y Position in NED frame [m] */
        public static final Field Y = MESSAGE.field("y");
        /** Z Position in NED frame (note, altitude is negative in NED) [m] */
        public static final Field Z = MESSAGE.field("z");
        /** X velocity in NED frame [m/s] */
        public static final Field VX = MESSAGE.field("vx");
        /** Y velocity in NED frame [m/s] */
        public static final Field VY = MESSAGE.field("vy");
        /** Z velocity in NED frame [m/s] */
        public static final Field VZ = MESSAGE.field("vz");
        /** X acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFX = MESSAGE.field("afx");
        /** Y acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFY = MESSAGE.field("afy");
        /** Z acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFZ = MESSAGE.field("afz");
        /** yaw setpoint [rad] */
        public static final Field YAW = MESSAGE.field("yaw");
        /** yaw rate setpoint [rad/s] */
        public static final Field YAW_RATE = MESSAGE.field("yaw_rate");

        private SetPositionTargetLocalNed() {
        }
    }

    /** POSITION_TARGET_LOCAL_NED (85): Reports the current commanded vehicle position, velocity, and acceleration as specified by the autopilot. */
    public static final class PositionTargetLocalNed {
        /** The message: id 85, CRC_EXTRA 140, at most 51 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("POSITION_TARGET_LOCAL_NED", 85, 140, "uint32_t time_boot_ms",
                "uint8_t coordinate_frame", "uint16_t type_mask", "float x", "float y", "float z", "float vx", "float vy",
                "float vz", "float afx", "float afy", "float afz", "float yaw", "float yaw_rate");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** Valid options are: MAV_FRAME_LOCAL_NED = 1, MAV_FRAME_LOCAL_OFFSET_NED = 7, MAV_FRAME_BODY_NED = 8, MAV_FRAME_BODY_OFFSET_NED = 9 */
        public static final Field COORDINATE_FRAME = MESSAGE.field("coordinate_frame");
        /** Bitmap to indicate which dimensions should be ignored by the vehicle. */
        public static final Field TYPE_MASK = MESSAGE.field("type_mask");
        /** X Position in NED frame [m] */
        public static final Field X = MESSAGE.field("x");
        /** Y Position in NED frame [m] */
        public static final Field Y = MESSAGE.field("y");
        /** Z Position in NED frame (note, altitude is negative in NED) [m] */
        public static final Field Z = MESSAGE.field("z");
        /** X velocity in NED frame [m/s] */
        public static final Field VX = MESSAGE.field("vx");
        /** Y velocity in NED frame [m/s] */
        public static final Field VY = MESSAGE.field("vy");
        /** Z velocity in NED frame [m/s] */
        public static final Field VZ = MESSAGE.field("vz");
        /** X acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFX = MESSAGE.field("afx");
        /** Y acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFY = MESSAGE.field("afy");
        /** Z acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFZ = MESSAGE.field("afz");
        /** yaw setpoint [rad] */
        public static final Field YAW = MESSAGE.field("yaw");
        /** yaw rate setpoint [rad/s] */
        public static final Field YAW_RATE = MESSAGE.field("yaw_rate");

        private PositionTargetLocalNed() {
        }
    }

    /** SET_POSITION_TARGET_GLOBAL_INT (86): Sets a desired vehicle position, velocity, and/or acceleration in a global coordinate system (WGS84). */
    public static final class SetPositionTargetGlobalInt {
        /** The message: id 86, CRC_EXTRA 5, at most 53 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("SET_POSITION_TARGET_GLOBAL_INT", 86, 5,
                "uint32_t time_boot_ms", "uint8_t target_system", "uint8_t target_component", "uint8_t coordinate_frame",
                "uint16_t type_mask", "int32_t lat_int", "int32_t lon_int", "float alt", "float vx", "float vy", "float vz",
                "float afx", "float afy", "float afz", "float yaw", "float yaw_rate");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** System ID */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** Component ID */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** Valid options are: MAV_FRAME_GLOBAL = 0, MAV_FRAME_GLOBAL_RELATIVE_ALT = 3, MAV_FRAME_GLOBAL_TERRAIN_ALT = 10 (MAV_FRAME_GLOBAL_INT, MAV_FRAME_GLOBAL_RELATIV... */
        public static final Field COORDINATE_FRAME = MESSAGE.field("coordinate_frame");
        /** Bitmap to indicate which dimensions should be ignored by the vehicle. */
        public static final Field TYPE_MASK = MESSAGE.field("type_mask");
        /** Latitude in WGS84 frame [degE7] */
        public static final Field LAT_INT = MESSAGE.field("lat_int");
        /** Longitude in WGS84 frame [degE7] */
        public static final Field LON_INT = MESSAGE.field("lon_int");
        /** Altitude (MSL, Relative to home, or AGL - depending on frame) [m] */
        public static final Field ALT = MESSAGE.field("alt");
        /** X velocity in NED frame [m/s] */
        public static final Field VX = MESSAGE.field("vx");
        /** Y velocity in NED frame [m/s] */
        public static final Field VY = MESSAGE.field("vy");
        /** Z velocity in NED frame [m/s] */
        public static final Field VZ = MESSAGE.field("vz");
        /** X acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFX = MESSAGE.field("afx");
        /** Y acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFY = MESSAGE.field("afy");
        /** Z acceleration or force (if bit 10 of type_mask is set) in NED frame in meter / s^2 or N [m/s/s] */
        public static final Field AFZ = MESSAGE.field("afz");
        /** yaw setpoint [rad] */
        public static final Field YAW = MESSAGE.field("yaw");
        /** yaw rate setpoint [rad/s] */
        public static final Field YAW_RATE = MESSAGE.field("yaw_rate");

        private SetPositionTargetGlobalInt() {
        }
    }

    /** RADIO_STATUS (109): Status generated by radio and injected into MAVLink stream. */
    public static final class RadioStatus {
        /** The message: id 109, CRC_EXTRA 185, at most 9 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("RADIO_STATUS", 109, 185, "uint8_t rssi", "uint8_t remrssi",
                "uint8_t txbuf", "uint8_t noise", "uint8_t remnoise", "uint16_t rxerrors", "uint16_t fixed");
        /** Local (message sender) received signal strength indication in device-dependent units/scale. */
        public static final Field RSSI = MESSAGE.field("rssi");
        /** Remote (message receiver) signal strength indication in device-dependent units/scale. */
        public static final Field REMRSSI = MESSAGE.field("remrssi");
        /** Remaining free transmitter buffer space. [%] */
        public static final Field TXBUF = MESSAGE.field("txbuf");
        /** Local background noise level. */
        public static final Field NOISE = MESSAGE.field("noise");
        /** Remote background noise level. */
        public static final Field REMNOISE = MESSAGE.field("remnoise");
        /** Count of radio packet receive errors (since boot). */
        public static final Field RXERRORS = MESSAGE.field("rxerrors");
        /** Count of error corrected radio packets (since boot). */
        public static final Field FIXED = MESSAGE.field("fixed");

        private RadioStatus() {
        }
    }

    /** TIMESYNC (111): Time synchronization message. */
    public static final class Timesync {
        /** The message: id 111, CRC_EXTRA 34, at most 16 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("TIMESYNC", 111, 34, "int64_t tc1", "int64_t ts1");
        /** Time sync timestamp 1. [ns] */
        public static final Field TC1 = MESSAGE.field("tc1");
        /** Time sync timestamp 2. [ns] */
        public static final Field TS1 = MESSAGE.field("ts1");

        private Timesync() {
        }
    }

    /** DISTANCE_SENSOR (132): Distance sensor information for an onboard rangefinder. */
    public static final class DistanceSensor {
        /** The message: id 132, CRC_EXTRA 85, at most 39 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("DISTANCE_SENSOR", 132, 85, "uint32_t time_boot_ms",
                "uint16_t min_distance", "uint16_t max_distance", "uint16_t current_distance", "uint8_t type", "uint8_t id",
                "uint8_t orientation", "uint8_t covariance", MessageType.EXTENSIONS, "float horizontal_fov", "float vertical_fov",
                "float[4] quaternion", "uint8_t signal_quality");
        /** Timestamp (time since system boot). [ms] */
        public static final Field TIME_BOOT_MS = MESSAGE.field("time_boot_ms");
        /** Minimum distance the sensor can measure [cm] */
        public static final Field MIN_DISTANCE = MESSAGE.field("min_distance");
        /** Maximum distance the sensor can measure [cm] */
        public static final Field MAX_DISTANCE = MESSAGE.field("max_distance");
        /** Current distance reading [cm] */
        public static final Field CURRENT_DISTANCE = MESSAGE.field("current_distance");
        /** Type of distance sensor. */
        public static final Field TYPE = MESSAGE.field("type");
        /** Onboard ID of the sensor */
        public static final Field ID = MESSAGE.field("id");
        /** Direction the sensor faces. */
        public static final Field ORIENTATION = MESSAGE.field("orientation");
        /** Measurement variance. [cm^2] */
        public static final Field COVARIANCE = MESSAGE.field("covariance");
        /** Horizontal Field of View (angle) where the distance measurement is valid and the field of view is known. [rad] */
        public static final Field HORIZONTAL_FOV = MESSAGE.field("horizontal_fov");
        /** Vertical Field of View (angle) where the distance measurement is valid and the field of view is known. [rad] */
        public static final Field VERTICAL_FOV = MESSAGE.field("vertical_fov");
        /** Quaternion of the sensor orientation in vehicle body frame (w, x, y, z order, zero-rotation is 1, 0, 0, 0). */
        public static final Field QUATERNION = MESSAGE.field("quaternion");
        /** Signal quality of the sensor. [%] */
        public static final Field SIGNAL_QUALITY = MESSAGE.field("signal_quality");

        private DistanceSensor() {
        }
    }

    /** BATTERY_STATUS (147): Battery information */
    public static final class BatteryStatus {
        /** The message: id 147, CRC_EXTRA 154, at most 54 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("BATTERY_STATUS", 147, 154, "uint8_t id",
                "uint8_t battery_function", "uint8_t type", "int16_t temperature", "uint16_t[10] voltages",
                "int16_t current_battery", "int32_t current_consumed", "int32_t energy_consumed", "int8_t battery_remaining",
                MessageType.EXTENSIONS, "int32_t time_remaining", "uint8_t charge_state", "uint16_t[4] voltages_ext",
                "uint8_t mode", "uint32_t fault_bitmask");
        /** Battery ID */
        public static final Field ID = MESSAGE.field("id");
        /** Function of the battery */
        public static final Field BATTERY_FUNCTION = MESSAGE.field("battery_function");
        /** Type (chemistry) of the battery */
        public static final Field TYPE = MESSAGE.field("type");
        /** Temperature of the battery. [cdegC] */
        public static final Field TEMPERATURE = MESSAGE.field("temperature");
        /** Battery voltage of cells 1 to 10 (see voltages_ext for cells 11-14). [mV] */
        public static final Field VOLTAGES = MESSAGE.field("voltages");
        /** Battery current, -1: autopilot does not measure the current. [cA] */
        public static final Field CURRENT_BATTERY = MESSAGE.field("current_battery");
        /** Consumed charge, -1: autopilot does not provide consumption estimate [mAh] */
        public static final Field CURRENT_CONSUMED = MESSAGE.field("current_consumed");
        /** Consumed energy, -1: autopilot does not provide energy consumption estimate [hJ] */
        public static final Field ENERGY_CONSUMED = MESSAGE.field("energy_consumed");
        /** Remaining battery energy. [%] */
        public static final Field BATTERY_REMAINING = MESSAGE.field("battery_remaining");
        /** Remaining battery time, 0: autopilot does not provide remaining battery time estimate [s] */
        public static final Field TIME_REMAINING = MESSAGE.field("time_remaining");
        /** State for extent of discharge, provided by autopilot for warning or external reactions */
        public static final Field CHARGE_STATE = MESSAGE.field("charge_state");
        /** Battery voltages for cells 11 to 14. [mV] */
        public static final Field VOLTAGES_EXT = MESSAGE.field("voltages_ext");
        /** Battery mode. */
        public static final Field MODE = MESSAGE.field("mode");
        /** Fault/health indications. */
        public static final Field FAULT_BITMASK = MESSAGE.field("fault_bitmask");

        private BatteryStatus() {
        }
    }

    /** AUTOPILOT_VERSION (148): Version and capability of autopilot software. */
    public static final class AutopilotVersion {
        /** The message: id 148, CRC_EXTRA 178, at most 78 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("AUTOPILOT_VERSION", 148, 178, "uint64_t capabilities",
                "uint32_t flight_sw_version", "uint32_t middleware_sw_version", "uint32_t os_sw_version", "uint32_t board_version",
                "uint8_t[8] flight_custom_version", "uint8_t[8] middleware_custom_version", "uint8_t[8] os_custom_version",
                "uint16_t vendor_id", "uint16_t product_id", "uint64_t uid", MessageType.EXTENSIONS, "uint8_t[18] uid2");
        /** Bitmap of capabilities */
        public static final Field CAPABILITIES = MESSAGE.field("capabilities");
        /** Firmware version number. */
        public static final Field FLIGHT_SW_VERSION = MESSAGE.field("flight_sw_version");
        /** Middleware version number */
        public static final Field MIDDLEWARE_SW_VERSION = MESSAGE.field("middleware_sw_version");
        /** Operating system version number */
        public static final Field OS_SW_VERSION = MESSAGE.field("os_sw_version");
        /** HW / board version (last 8 bits should be silicon ID, if any). */
        public static final Field BOARD_VERSION = MESSAGE.field("board_version");
        /** Custom version field, commonly the first 8 bytes of the git hash. */
        public static final Field FLIGHT_CUSTOM_VERSION = MESSAGE.field("flight_custom_version");
        /** Custom version field, commonly the first 8 bytes of the git hash. */
        public static final Field MIDDLEWARE_CUSTOM_VERSION = MESSAGE.field("middleware_custom_version");
        /** Custom version field, commonly the first 8 bytes of the git hash. */
        public static final Field OS_CUSTOM_VERSION = MESSAGE.field("os_custom_version");
        /** ID of the board vendor */
        public static final Field VENDOR_ID = MESSAGE.field("vendor_id");
        /** ID of the product */
        public static final Field PRODUCT_ID = MESSAGE.field("product_id");
        /** UID if provided by hardware (see uid2) */
        public static final Field UID = MESSAGE.field("uid");
        /** UID if provided by hardware (supersedes the uid field. */
        public static final Field UID2 = MESSAGE.field("uid2");

        private AutopilotVersion() {
        }
    }

    /** HOME_POSITION (242): This message can be requested by sending the MAV_CMD_GET_HOME_POSITION command. */
    public static final class HomePosition {
        /** The message: id 242, CRC_EXTRA 104, at most 60 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("HOME_POSITION", 242, 104, "int32_t latitude",
                "int32_t longitude", "int32_t altitude", "float x", "float y", "float z", "float[4] q", "float approach_x",
                "float approach_y", "float approach_z", MessageType.EXTENSIONS, "uint64_t time_usec");
        /** Latitude (WGS84) [degE7] */
        public static final Field LATITUDE = MESSAGE.field("latitude");
        /** Longitude (WGS84) [degE7] */
        public static final Field LONGITUDE = MESSAGE.field("longitude");
        /** Altitude (MSL). [mm] */
        public static final Field ALTITUDE = MESSAGE.field("altitude");
        /** Local X position of this position in the local coordinate frame [m] */
        public static final Field X = MESSAGE.field("x");
        /** Local Y position of this position in the local coordinate frame [m] */
        public static final Field Y = MESSAGE.field("y");
        /** Local Z position of this position in the local coordinate frame [m] */
        public static final Field Z = MESSAGE.field("z");
        /** World to surface normal and heading transformation of the takeoff position. */
        public static final Field Q = MESSAGE.field("q");
        /** Local X position of the end of the approach vector. [m] */
        public static final Field APPROACH_X = MESSAGE.field("approach_x");
        /** Local Y position of the end of the approach vector. [m] */
        public static final Field APPROACH_Y = MESSAGE.field("approach_y");
        /** Local Z position of the end of the approach vector. [m] */
        public static final Field APPROACH_Z = MESSAGE.field("approach_z");
        /** Timestamp (UNIX Epoch time or time since system boot). [us] */
        public static final Field TIME_USEC = MESSAGE.field("time_usec");

        private HomePosition() {
        }
    }

    /** EXTENDED_SYS_STATE (245): Provides state for additional features */
    public static final class ExtendedSysState {
        /** The message: id 245, CRC_EXTRA 130, at most 2 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("EXTENDED_SYS_STATE", 245, 130, "uint8_t vtol_state",
                "uint8_t landed_state");
        /** The VTOL state if applicable. */
        public static final Field VTOL_STATE = MESSAGE.field("vtol_state");
        /** The landed state. */
        public static final Field LANDED_STATE = MESSAGE.field("landed_state");

        private ExtendedSysState() {
        }
    }

    /** STATUSTEXT (253): Status text message. */
    public static final class Statustext {
        /** The message: id 253, CRC_EXTRA 83, at most 54 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("STATUSTEXT", 253, 83, "uint8_t severity", "char[50] text",
                MessageType.EXTENSIONS, "uint16_t id", "uint8_t chunk_seq");
        /** Severity of status. */
        public static final Field SEVERITY = MESSAGE.field("severity");
        /** Status text message, without null termination character. */
        public static final Field TEXT = MESSAGE.field("text");
        /** Unique (opaque) identifier for this statustext message. */
        public static final Field ID = MESSAGE.field("id");
        /** This chunk's sequence number; indexing is from zero. */
        public static final Field CHUNK_SEQ = MESSAGE.field("chunk_seq");

        private Statustext() {
        }
    }

    /** SETUP_SIGNING (256): Setup a MAVLink2 signing key. */
    public static final class SetupSigning {
        /** The message: id 256, CRC_EXTRA 71, at most 42 payload bytes. */
        public static final MessageType MESSAGE = MessageType.define("SETUP_SIGNING", 256, 71, "uint8_t target_system",
                "uint8_t target_component", "uint8_t[32] secret_key", "uint64_t initial_timestamp");
        /** system id of the target */
        public static final Field TARGET_SYSTEM = MESSAGE.field("target_system");
        /** component ID of the target */
        public static final Field TARGET_COMPONENT = MESSAGE.field("target_component");
        /** signing key */
        public static final Field SECRET_KEY = MESSAGE.field("secret_key");
        /** initial timestamp */
        public static final Field INITIAL_TIMESTAMP = MESSAGE.field("initial_timestamp");

        private SetupSigning() {
        }
    }
}
