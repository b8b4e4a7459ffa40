"""Flies a MAVLink vehicle with MAVSDK (PyPI mavsdk 4.1.0), as a MAVSDK user would, and says what
happened, one line per step: 'OK step detail' or 'FAIL step why' (then exits 1).

    python3 mavsdk_flight.py CONNECTION copter|boat

CONNECTION is a MAVSDK connection URL (udpin://127.0.0.1:14550 to hear a vehicle that sends there).
copter: arm, take off, offboard position then body velocity, land (both dialects).
boat:   arm, offboard body velocity, then position (a boat has no take-off).
"""
import asyncio
import math
import sys
import time

from mavsdk.asyncio import Configuration, ComponentType, Mavsdk
from mavsdk.asyncio.plugins.action import ActionAsync
from mavsdk.asyncio.plugins.offboard import OffboardAsync
from mavsdk.asyncio.plugins.telemetry import TelemetryAsync
from mavsdk.plugins.offboard import PositionNedYaw, VelocityBodyYawspeed

TIMEOUT = 60.0


def ok(step, detail=''):
    print('OK', step, detail, flush=True)


def fail(step, why):
    print('FAIL', step, why, flush=True)
    sys.exit(1)


async def until(step, check, timeout=TIMEOUT):
    """Polls check() (async, returns (done, detail)) every 0.2 s until done or the deadline."""
    end = time.monotonic() + timeout
    detail = ''
    while time.monotonic() < end:
        done, detail = await check()
        if done:
            ok(step, detail)
            return
        await asyncio.sleep(0.2)
    fail(step, 'not within %.0f s; last %s' % (timeout, detail))


async def main(url, kind):
    config = Configuration.create_with_component_type(ComponentType.GROUND_STATION)
    async with Mavsdk(config) as mavsdk:
        await mavsdk.add_any_connection(url)
        system = await mavsdk.first_autopilot(timeout_s=20.0)
        if system is None:
            fail('discover', 'no autopilot heard on ' + url)
        ok('discover', 'autopilot %s' % (await system.autopilot_type()))
        action = ActionAsync(system)
        offboard = OffboardAsync(system)
        telemetry = TelemetryAsync(system)

        async def ned():
            """The local position, once MAVSDK has one (before LOCAL_POSITION_NED it reports NaN)."""
            end = time.monotonic() + 20
            while True:
                p = (await telemetry.position_velocity_ned()).position
                if not math.isnan(p.north_m) or time.monotonic() > end:
                    return p
                await asyncio.sleep(0.2)

        try:
            await action.arm()
        except Exception as e:
            fail('arm', repr(e))
        ok('arm')
        if kind == 'copter':
            try:
                await action.takeoff()
            except Exception as e:
                fail('takeoff', repr(e))
            ok('takeoff-accepted')

            async def up():
                p = await telemetry.position()
                return p.relative_altitude_m > 1.5, 'altitude %.2f' % p.relative_altitude_m
            await until('takeoff', up)
            start = await ned()
            target = PositionNedYaw(start.north_m + 3.0, start.east_m + 2.0, -2.5, 0.0)
            await offboard.set_position_ned(target)
            await asyncio.sleep(1.5)   # PX4 wants the setpoint stream before OFFBOARD
            try:
                await offboard.start()
            except Exception as e:
                fail('offboard-start', repr(e))
            ok('offboard-start')

            async def there():
                p = await ned()
                d = math.hypot(p.north_m - target.north_m, p.east_m - target.east_m)
                return d < 0.3 and abs(p.down_m + 2.5) < 0.3, 'distance %.2f down %.2f' % (d, p.down_m)
            await until('offboard-position', there)
            before = await ned()
            await offboard.set_velocity_body(VelocityBodyYawspeed(1.0, 0.0, 0.0, 0.0))

            async def moved():
                p = await ned()
                d = math.hypot(p.north_m - before.north_m, p.east_m - before.east_m)
                return d > 1.5, 'moved %.2f' % d
            await until('offboard-velocity', moved)
            await offboard.set_velocity_body(VelocityBodyYawspeed(0.0, 0.0, 0.0, 0.0))
            await offboard.stop()
            ok('offboard-stop')
            try:
                await action.land()
            except Exception as e:
                fail('land', repr(e))

            async def landed():
                air = await telemetry.in_air()
                return not air, 'in air %s' % air
            await until('landed', landed)
        else:
            start = await ned()
            await offboard.set_velocity_body(VelocityBodyYawspeed(1.0, 0.0, 0.0, 0.0))
            await asyncio.sleep(1.5)
            try:
                await offboard.start()
            except Exception as e:
                fail('offboard-start', repr(e))
            ok('offboard-start')

            async def sailed():
                p = await ned()
                d = math.hypot(p.north_m - start.north_m, p.east_m - start.east_m)
                return d > 2.0, 'moved %.2f' % d
            await until('offboard-velocity', sailed)
            here = await ned()
            target = PositionNedYaw(here.north_m + 3.0, here.east_m - 2.0, 0.0, 0.0)
            await offboard.set_position_ned(target)

            async def arrived():
                p = await ned()
                d = math.hypot(p.north_m - target.north_m, p.east_m - target.east_m)
                return d < 1.0, 'distance %.2f' % d
            await until('offboard-position', arrived)
            await offboard.stop()
            ok('offboard-stop')
            try:
                await action.takeoff()
                fail('no-takeoff', 'a boat took off')
            except Exception as e:
                ok('no-takeoff', type(e).__name__)
            await action.disarm()
            ok('disarm')
        print('DONE', flush=True)


if __name__ == '__main__':
    asyncio.run(main(sys.argv[1], sys.argv[2]))
