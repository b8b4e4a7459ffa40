"""A small Foxglove WebSocket client (protocol: foxglove.sdk.v1 / foxglove.websocket.v1), written
from the protocol, for RoboMW's integration tests. It is run against RoboMW's server and against
foxglove-sdk's own reference server in the same test, so the check itself is shown right.

    python foxglove_probe.py URL TOPIC [--messages N] [--drive TOPIC --seconds S --linear V --angular W]

Prints one JSON object per line: the subprotocol chosen, serverInfo, the channel of TOPIC (its
schema parsed), the first N messages on it (log time, payload), whether a handshake offering only
the legacy name is taken, the first TIME frame (a server with the time capability), and with
--drive, the poses before and after publishing Twists.
"""
import argparse
import asyncio
import json
import struct

from websockets.asyncio.client import connect
from websockets.exceptions import InvalidStatus

BOTH = ["foxglove.sdk.v1", "foxglove.websocket.v1"]


def say(**fields):
    print(json.dumps(fields), flush=True)


async def next_text(ws, op):
    while True:
        m = await ws.recv()
        if isinstance(m, str) and json.loads(m).get("op") == op:
            return json.loads(m)


seen_time = False


async def next_message(ws, subscription):
    global seen_time
    while True:
        m = await ws.recv()
        if isinstance(m, bytes) and m[0] == 2 and not seen_time:  # TIME: the server's clock (the time capability)
            seen_time = True
            say(serverTime=struct.unpack_from("<BQ", m)[1])
        if isinstance(m, bytes) and m[0] == 1:
            opcode, sub, log_time = struct.unpack_from("<BIQ", m)
            if sub == subscription:
                return log_time, json.loads(m[13:])


async def main(a):
    try:
        async with connect(a.url, subprotocols=["foxglove.websocket.v1"], open_timeout=10):
            say(legacy="accepted")
    except InvalidStatus as e:
        say(legacy="rejected", status=e.response.status_code)
    async with connect(a.url, subprotocols=BOTH, open_timeout=10, max_size=None) as ws:
        say(subprotocol=ws.subprotocol)
        first = json.loads(await ws.recv())
        assert first["op"] == "serverInfo", first
        say(serverInfo=first)
        channel = None
        while channel is None:
            advertise = await next_text(ws, "advertise")
            channel = next((c for c in advertise["channels"] if c["topic"] == a.topic), None)
        assert channel["encoding"] == "json", channel
        channel["schema"] = json.loads(channel["schema"])  # a JSON Schema, for encoding json
        say(channel=channel)
        await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 42, "channelId": channel["id"]}]}))
        for _ in range(a.messages):
            log_time, payload = await next_message(ws, 42)
            say(message=payload, logTime=log_time)
        if a.drive:
            assert "clientPublish" in first["capabilities"], first
            before = (await next_message(ws, 42))[1]
            await ws.send(json.dumps({"op": "advertise", "channels": [
                {"id": 7, "topic": a.drive, "encoding": "json", "schemaName": "geometry_msgs/Twist"}]}))
            twist = json.dumps({"linear": {"x": a.linear, "y": 0, "z": 0}, "angular": {"x": 0, "y": 0, "z": a.angular}}).encode()
            loop = asyncio.get_running_loop()
            end = loop.time() + a.seconds
            next_send = loop.time()
            while loop.time() < end:  # a teleop panel publishes at 10 Hz while a button is held
                await ws.send(struct.pack("<BI", 1, 7) + twist)
                next_send += 0.1
                while (left := next_send - loop.time()) > 0:  # meanwhile, read (and drop) what comes
                    try:
                        await asyncio.wait_for(ws.recv(), left)
                    except asyncio.TimeoutError:
                        break
            after = (await next_message(ws, 42))[1]
            await ws.send(json.dumps({"op": "unadvertise", "channelIds": [7]}))
            say(before=before, after=after)
    say(done=True)


if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("url")
    p.add_argument("topic")
    p.add_argument("--messages", type=int, default=3)
    p.add_argument("--drive")
    p.add_argument("--seconds", type=float, default=2.0)
    p.add_argument("--linear", type=float, default=0.2)
    p.add_argument("--angular", type=float, default=0.0)
    asyncio.run(main(p.parse_args()))
