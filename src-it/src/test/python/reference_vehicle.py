"""A small MAVLink vehicle written with pymavlink 2.4.50 alone, to check RoboMW's platform: mavlink
driver against something that is not RoboMW's own emulator. It sends to a ground station (as
ArduPilot SITL's --out), behaves as ArduPilot or PX4 document the parts a ground station uses, and
prints what it receives, one line each, for the test to read:

    RX HEARTBEAT type=6 autopilot=8 from=255/190
    RX COMMAND_LONG command=400 p1=1.0 ... from=255/190
    RX SET_MODE / RX SET_POSITION_TARGET_LOCAL_NED frame=1 mask=2552 x=.. / RX PARAM_SET id=.. value=..
    STATE armed=1 mode=4 north=.. east=.. down=.. yaw=..   (once a second)

    python3 reference_vehicle.py --out 127.0.0.1:14550 [--type copter|boat] [--autopilot ardupilot|px4]
                                 [--drop-first-arm] [--takeoff-in-progress]

--drop-first-arm ignores the first COMPONENT_ARM_DISARM (the driver must send it again);
--takeoff-in-progress answers NAV_TAKEOFF with IN_PROGRESS, and ACCEPTED 1 s later.
Its dynamics are a first-order position and velocity model (gain 1/s, 2 m/s at most).
"""
import argparse
import math
import sys
import time

import os
os.environ.setdefault('MAVLINK20', '1')   # pymavlink speaks MAVLink 1 unless told (signing needs 2)
from pymavlink import mavutil  # noqa: E402

M = mavutil.mavlink


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--out', required=True)
    ap.add_argument('--type', default='copter')
    ap.add_argument('--autopilot', default='ardupilot')
    ap.add_argument('--drop-first-arm', action='store_true')
    ap.add_argument('--takeoff-in-progress', action='store_true')
    a = ap.parse_args()
    copter = a.type == 'copter'
    px4 = a.autopilot == 'px4'
    conn = mavutil.mavlink_connection('udpout:' + a.out, source_system=1, source_component=1, dialect='common')
    mav = conn.mav
    mav_type = M.MAV_TYPE_QUADROTOR if copter else M.MAV_TYPE_SURFACE_BOAT
    autopilot = M.MAV_AUTOPILOT_PX4 if px4 else M.MAV_AUTOPILOT_ARDUPILOTMEGA
    guided = (6 << 16) if px4 else (4 if copter else 15)
    hold = (4 << 16 | 3 << 24) if px4 else (5 if copter else 4)
    land_mode = (4 << 16 | 6 << 24) if px4 else 9
    s = dict(n=0.0, e=0.0, d=0.0, vn=0.0, ve=0.0, vd=0.0, yaw=0.0, yaw_rate=0.0, armed=False, mode=hold if px4 else 0,
             target=None, vel=None, target_yaw=None, target_rate=None, takeoff=None, landing=False, landed=True,
             stream_since=None, last_sp=0.0)
    params = {'MIS_TAKEOFF_ALT': 2.5}
    dropped_arm = [False]
    pending_takeoff = []
    start = time.monotonic()
    nxt = dict(hb=0.0, slow=0.0, fast=0.0, state=0.0)
    print('READY', flush=True)

    def ack(msg, command, result):
        mav.command_ack_send(command, result, 0, 0, msg.get_srcSystem(), msg.get_srcComponent())

    def handle(m):
        t = m.get_type()
        src = '%d/%d' % (m.get_srcSystem(), m.get_srcComponent())
        if t == 'HEARTBEAT':
            print('RX HEARTBEAT type=%d autopilot=%d from=%s' % (m.type, m.autopilot, src), flush=True)
        elif t == 'COMMAND_LONG':
            print('RX COMMAND_LONG command=%d p1=%r p2=%r p3=%r p7=%r target=%d/%d from=%s' % (
                m.command, m.param1, m.param2, m.param3, m.param7, m.target_system, m.target_component, src), flush=True)
            if m.target_system != 1:
                return
            if m.command == M.MAV_CMD_COMPONENT_ARM_DISARM:
                if a.drop_first_arm and not dropped_arm[0]:
                    dropped_arm[0] = True
                    return
                s['armed'] = m.param1 >= 0.5
                ack(m, m.command, M.MAV_RESULT_ACCEPTED)
            elif m.command == M.MAV_CMD_DO_SET_MODE:
                custom = (int(m.param2) << 16 | (0 if math.isnan(m.param3) else int(m.param3)) << 24) if px4 else int(m.param2)
                if px4 and custom == guided and (s['stream_since'] is None or now() - s['stream_since'] < 1.0 or now() - s['last_sp'] > 0.5):
                    ack(m, m.command, M.MAV_RESULT_TEMPORARILY_REJECTED)
                    return
                s['mode'] = custom
                ack(m, m.command, M.MAV_RESULT_ACCEPTED)
            elif m.command == M.MAV_CMD_NAV_TAKEOFF:
                if not copter:
                    ack(m, m.command, M.MAV_RESULT_UNSUPPORTED)
                    return
                if not s['armed'] or (not px4 and s['mode'] != guided):
                    ack(m, m.command, M.MAV_RESULT_FAILED)
                    return
                alt = params['MIS_TAKEOFF_ALT'] if px4 or math.isnan(m.param7) else m.param7
                s['takeoff'] = alt
                s['landed'] = False
                if px4:
                    s['mode'] = 4 << 16 | 2 << 24
                if a.takeoff_in_progress:
                    ack(m, m.command, M.MAV_RESULT_IN_PROGRESS)
                    pending_takeoff.append((now() + 1.0, m))
                else:
                    ack(m, m.command, M.MAV_RESULT_ACCEPTED)
            elif m.command == M.MAV_CMD_NAV_LAND:
                s['mode'] = land_mode
                s['landing'] = True
                s['target'] = None
                s['vel'] = None
                ack(m, m.command, M.MAV_RESULT_ACCEPTED)
            else:
                ack(m, m.command, M.MAV_RESULT_UNSUPPORTED)
        elif t == 'SET_POSITION_TARGET_LOCAL_NED':
            print('RX SET_POSITION_TARGET_LOCAL_NED frame=%d mask=%d x=%.3f y=%.3f z=%.3f vx=%.3f vy=%.3f yaw=%.3f yaw_rate=%.3f t=%.3f' % (
                m.coordinate_frame, m.type_mask, m.x, m.y, m.z, m.vx, m.vy, m.yaw, m.yaw_rate, now()), flush=True)
            if s['stream_since'] is None or now() - s['last_sp'] > 0.5:
                s['stream_since'] = now()
            s['last_sp'] = now()
            if s['mode'] != guided:
                return
            if not (m.type_mask & 3):
                s['target'] = (m.x, m.y, m.z if not (m.type_mask & 4) else s['d'])
                s['vel'] = None
            elif not (m.type_mask & 8):
                if m.coordinate_frame in (M.MAV_FRAME_BODY_NED, M.MAV_FRAME_BODY_OFFSET_NED):
                    c, sn = math.cos(s['yaw']), math.sin(s['yaw'])
                    s['vel'] = (m.vx * c - m.vy * sn, m.vx * sn + m.vy * c, m.vz, now())
                else:
                    s['vel'] = (m.vx, m.vy, m.vz, now())
                s['target'] = None
            s['target_yaw'] = None if m.type_mask & 1024 else m.yaw
            s['target_rate'] = None if m.type_mask & 2048 else m.yaw_rate
        elif t == 'PARAM_SET':
            pid = m.param_id if isinstance(m.param_id, str) else m.param_id.decode()
            print('RX PARAM_SET id=%s value=%r' % (pid, m.param_value), flush=True)
            params[pid] = m.param_value
            mav.param_value_send(pid.encode(), m.param_value, M.MAV_PARAM_TYPE_REAL32, len(params), 0)
        elif t == 'SET_MODE':
            print('RX SET_MODE custom=%d from=%s' % (m.custom_mode, src), flush=True)

    def now():
        return time.monotonic() - start

    def step(dt):
        if not s['armed']:
            s['vn'] = s['ve'] = s['vd'] = 0.0
            return
        tv = [0.0, 0.0, 0.0]
        if s['takeoff'] is not None:
            tv[2] = max(-1.5, min(1.5, (-s['takeoff'] - s['d'])))
            if abs(-s['takeoff'] - s['d']) < 0.05:
                s['takeoff'] = None
                s['target'] = (s['n'], s['e'], s['d'])
                if px4:
                    s['mode'] = hold
        elif s['landing']:
            tv[2] = 0.7
            if s['d'] >= 0:
                s['d'] = 0.0
                s['landing'] = False
                s['landed'] = True
                s['armed'] = False
        elif s['target'] is not None:
            for i, k in enumerate('ned'):
                tv[i] = s['target'][i] - s[k]
        elif s['vel'] is not None and now() - s['vel'][3] < (1.0 if px4 else 3.0):
            tv = list(s['vel'][:3])
        if px4 and s['mode'] == guided and now() - s['last_sp'] > 1.0:
            s['mode'] = hold
            s['target'] = (s['n'], s['e'], s['d'])
            mav.statustext_send(M.MAV_SEVERITY_WARNING, b'Failsafe: offboard lost')
        if not copter:
            tv[2] = 0.0
        h = math.hypot(tv[0], tv[1])
        if h > 2.0:
            tv[0] *= 2.0 / h
            tv[1] *= 2.0 / h
        for i, k in enumerate(('vn', 've', 'vd')):
            s[k] += (tv[i] - s[k]) * min(1.0, dt / 0.3)
        s['n'] += s['vn'] * dt
        s['e'] += s['ve'] * dt
        s['d'] = min(0.0, s['d'] + s['vd'] * dt) if copter else 0.0
        rate = 0.0
        if s['target_rate'] is not None:
            rate = s['target_rate']
        elif s['target_yaw'] is not None:
            err = math.atan2(math.sin(s['target_yaw'] - s['yaw']), math.cos(s['target_yaw'] - s['yaw']))
            rate = max(-1.5, min(1.5, 2 * err))
        s['yaw'] = math.atan2(math.sin(s['yaw'] + rate * dt), math.cos(s['yaw'] + rate * dt))
        s['yaw_rate'] = rate

    last = time.monotonic()
    while True:
        m = conn.recv_match(blocking=True, timeout=0.01)
        while m is not None:
            if m.get_type() != 'BAD_DATA':
                handle(m)
            m = conn.recv_match(blocking=False)
        t = time.monotonic()
        step(t - last)
        last = t
        for when, msg in list(pending_takeoff):
            if now() >= when:
                pending_takeoff.remove((when, msg))
                ack(msg, M.MAV_CMD_NAV_TAKEOFF, M.MAV_RESULT_ACCEPTED)
        n = now()
        base = M.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED | (M.MAV_MODE_FLAG_SAFETY_ARMED if s['armed'] else 0)
        if n >= nxt['hb']:
            nxt['hb'] = n + 1.0
            mav.heartbeat_send(mav_type, autopilot, base, s['mode'], M.MAV_STATE_ACTIVE if s['armed'] else M.MAV_STATE_STANDBY)
        if n >= nxt['slow']:
            nxt['slow'] = n + 1.0
            landed = M.MAV_LANDED_STATE_ON_GROUND if s['landed'] and copter else (M.MAV_LANDED_STATE_IN_AIR if copter else 0)
            mav.extended_sys_state_send(0, landed)
            mav.sys_status_send(0x2F, 0x2F, 0x2F, 100, 15800, 500, 80, 0, 0, 0, 0, 0, 0)
        if n >= nxt['fast']:
            nxt['fast'] = n + 0.1
            ms = int(n * 1000)
            mav.local_position_ned_send(ms, s['n'], s['e'], s['d'], s['vn'], s['ve'], s['vd'])
            mav.attitude_send(ms, 0, 0, s['yaw'], 0, 0, s['yaw_rate'])
            mav.global_position_int_send(ms, int((50.154 + s['n'] / 111320.0) * 1e7), int((-5.0675 + s['e'] / 71400.0) * 1e7),
                                         int(-s['d'] * 1000), int(-s['d'] * 1000), int(s['vn'] * 100), int(s['ve'] * 100),
                                         int(s['vd'] * 100), int((math.degrees(s['yaw']) % 360) * 100))
            mav.distance_sensor_send(ms, 5, 4000, max(5, int(-s['d'] * 100)), M.MAV_DISTANCE_SENSOR_LASER, 0,
                                     M.MAV_SENSOR_ROTATION_PITCH_270, 255)
        if n >= nxt['state']:
            nxt['state'] = n + 1.0
            print('STATE armed=%d mode=%d north=%.2f east=%.2f down=%.2f yaw=%.3f' % (
                s['armed'], s['mode'], s['n'], s['e'], s['d'], s['yaw']), flush=True)


if __name__ == '__main__':
    try:
        main()
    except KeyboardInterrupt:
        sys.exit(0)
