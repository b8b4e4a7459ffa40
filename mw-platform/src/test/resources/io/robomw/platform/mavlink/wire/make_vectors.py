"""Makes pymavlink-vectors.txt: MAVLink frames encoded by pymavlink, for MavlinkVectorsTest.

Run with pymavlink 2.4.50 (pip install pymavlink==2.4.50):
    python3 make_vectors.py > pymavlink-vectors.txt

Each line: name | frame as hex | sysid/compid/seq | fields (name=value;...; arrays as a,b,c)
Signed frames use the key SHA-256(passphrase) as MAVProxy's 'signing setup' makes it, a link id
and a starting timestamp given on the line (key passphrase@link@timestamp), or '-' when unsigned.
"""
import hashlib
import math
from pymavlink.dialects.v20 import common as mav


class Sink:
    def write(self, b):
        pass


def value_for(ftype, index, salt):
    """A deterministic, non-trivial value of a field type (every byte of the field used)."""
    k = index * 7 + salt
    if ftype == 'char':
        return None
    if ftype == 'float':
        return float(('%.3f' % ((k * 1.37 - 11.5) * (1 if k % 2 else -1))))
    if ftype == 'double':
        return (k * 3.1416 - 7.25)
    bits = int(ftype.replace('uint', '').replace('int', '').replace('_t', ''))
    signed = not ftype.startswith('u')
    v = (0x0123456789ABCDEF * (k + 3)) & ((1 << bits) - 1)
    if v == 0:
        v = 1
    if signed and v >= 1 << (bits - 1):
        v -= 1 << bits
    return v


def fill(cls, salt, zero_tail=False, text=None):
    args = []
    for i, name in enumerate(cls.fieldnames):
        t = cls.fieldtypes[i]
        n = cls.array_lengths[cls.ordered_fieldnames.index(name)]
        if t == 'char':
            args.append((text or 'RoboMW says hello')[:n].encode())
        elif n:
            args.append([value_for(t, i * 31 + j, salt) for j in range(n)])
        else:
            args.append(value_for(t, i, salt))
    if zero_tail:  # zero the last fields in wire order: the frame is cut (truncation)
        for name in cls.ordered_fieldnames[len(cls.ordered_fieldnames) // 2:]:
            i = cls.fieldnames.index(name)
            t = cls.fieldtypes[i]
            n = cls.array_lengths[cls.ordered_fieldnames.index(name)]
            args[i] = b'' if t == 'char' else ([0] * n if n else (0.0 if t in ('float', 'double') else 0))
    return args


def fmt(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, list):
        return ','.join(fmt(x) for x in v)
    if isinstance(v, float):
        return repr(v)
    return str(v)


def emit(name, msg_cls, args, sysid=1, compid=1, seq=0, signing=None):
    m = mav.MAVLink(Sink(), srcSystem=sysid, srcComponent=compid)
    m.seq = seq
    sig = '-'
    if signing:
        phrase, link, ts = signing
        m.signing.secret_key = hashlib.sha256(phrase.encode()).digest()
        m.signing.link_id = link
        m.signing.timestamp = ts
        m.signing.sign_outgoing = True
        sig = '%s@%d@%d' % (phrase, link, ts)
    msg = msg_cls(*args)
    frame = msg.pack(m)
    fields = ';'.join('%s=%s' % (n, fmt(a)) for n, a in zip(msg_cls.fieldnames, args))
    print('%s|%s|%d/%d/%d|%s|%s' % (name, frame.hex(), sysid, compid, seq, sig, fields))


emit('heartbeat', mav.MAVLink_heartbeat_message, [2, 3, 0x81, 4, 4, 3])
emit('heartbeat-signed', mav.MAVLink_heartbeat_message, [2, 3, 0x81, 4, 4, 3], signing=('robomw', 0, 1000))
emit('command-ack', mav.MAVLink_command_ack_message, [400, 0, 0, 0, 0, 0])
emit('heartbeat-zero', mav.MAVLink_heartbeat_message, [0, 0, 0, 0, 0, 0])
names = ['SYS_STATUS', 'GPS_RAW_INT', 'ATTITUDE', 'LOCAL_POSITION_NED', 'GLOBAL_POSITION_INT', 'MISSION_ITEM_INT',
         'COMMAND_LONG', 'COMMAND_INT', 'COMMAND_ACK', 'SET_POSITION_TARGET_LOCAL_NED', 'DISTANCE_SENSOR',
         'BATTERY_STATUS', 'AUTOPILOT_VERSION', 'HOME_POSITION', 'EXTENDED_SYS_STATE', 'STATUSTEXT', 'PARAM_VALUE',
         'PARAM_SET', 'MISSION_CURRENT', 'SETUP_SIGNING', 'TIMESYNC', 'VFR_HUD']
for k, n in enumerate(names):
    cls = getattr(mav, 'MAVLink_' + n.lower() + '_message')
    emit(n.lower(), cls, fill(cls, k), sysid=1 + k, compid=1, seq=k * 11)
    emit(n.lower() + '-cut', cls, fill(cls, k, zero_tail=True), sysid=1, compid=1, seq=200 + k)
for k, n in enumerate(['COMMAND_LONG', 'SET_POSITION_TARGET_LOCAL_NED', 'STATUSTEXT', 'MISSION_ITEM_INT']):
    cls = getattr(mav, 'MAVLink_' + n.lower() + '_message')
    emit(n.lower() + '-signed', cls, fill(cls, 40 + k), sysid=255, compid=190, seq=k,
         signing=('correct horse battery staple', k + 1, 378_000_000_000 + k * 12_345))
