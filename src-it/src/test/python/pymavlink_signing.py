"""Talks to a signing MAVLink vehicle with pymavlink 2.4.50 and says whether it listened, one line
per step ('OK step detail' or 'FAIL step why', then exit 1).

    python3 pymavlink_signing.py CONNECTION PASSPHRASE_FILE right|wrong|unsigned

The key is SHA-256 of the passphrase, as MAVProxy's 'signing setup' makes it. With the right key
the vehicle must answer a signed COMMAND_LONG (arm) with COMMAND_ACK ACCEPTED, and its own frames
must carry valid signatures; with a wrong key, or unsigned, it must not answer at all.
"""
import hashlib
import sys
import time

import os
os.environ.setdefault('MAVLINK20', '1')   # pymavlink speaks MAVLink 1 unless told (signing needs 2)
from pymavlink import mavutil  # noqa: E402


def ok(step, detail=''):
    print('OK', step, detail, flush=True)


def fail(step, why):
    print('FAIL', step, why, flush=True)
    sys.exit(1)


def main(url, phrase_file, mode):
    phrase = open(phrase_file, encoding='utf-8').read().strip()
    key = hashlib.sha256(phrase.encode('utf-8')).digest()
    if mode == 'wrong':
        key = hashlib.sha256((phrase + ' (wrong)').encode('utf-8')).digest()
    conn = mavutil.mavlink_connection(url, source_system=255, source_component=190, dialect='common')
    if mode != 'unsigned':
        # pymavlink's own signing: key, link id, timestamp from now, sign everything sent
        conn.setup_signing(key, sign_outgoing=True, allow_unsigned_callback=None)
    conn.mav.heartbeat_send(mavutil.mavlink.MAV_TYPE_GCS, mavutil.mavlink.MAV_AUTOPILOT_INVALID, 0, 0, 0)
    hb = conn.wait_heartbeat(timeout=20)
    if hb is None:
        if mode == 'right':
            fail('heartbeat', 'no HEARTBEAT accepted in 20 s')
        # with a wrong key pymavlink drops the vehicle's signed frames: that is the point
        ok('heartbeat', 'none accepted: the frames are signed with another key')
    else:
        ok('heartbeat', 'type %d signed %s' % (hb.type, hb.get_signed()))
        if mode == 'right' and not hb.get_signed():
            fail('signed', 'the vehicle sends unsigned frames')
    deadline = time.time() + (10 if mode == 'right' else 4)
    answered = None
    sent = 0
    while time.time() < deadline and answered is None:
        if sent == 0 or time.time() > last + 1.0:
            conn.mav.command_long_send(1, 1, mavutil.mavlink.MAV_CMD_COMPONENT_ARM_DISARM, 0, 1, 0, 0, 0, 0, 0, 0)
            sent += 1
            last = time.time()
        m = conn.recv_match(type='COMMAND_ACK', blocking=True, timeout=0.5)
        if m is not None and m.command == mavutil.mavlink.MAV_CMD_COMPONENT_ARM_DISARM:
            answered = m
    if mode == 'right':
        if answered is None:
            fail('arm', 'no COMMAND_ACK to a signed arm in 10 s')
        if answered.result != mavutil.mavlink.MAV_RESULT_ACCEPTED or answered.target_system != 255:
            fail('arm', 'ACK %s' % answered)
        ok('arm', 'ACCEPTED, addressed to %d/%d' % (answered.target_system, answered.target_component))
    else:
        if answered is not None:
            fail('refused', 'the vehicle answered an arm signed with the wrong key or unsigned: %s' % answered)
        ok('refused', 'no answer to %d arm commands' % sent)
    print('DONE', flush=True)


if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2], sys.argv[3])
