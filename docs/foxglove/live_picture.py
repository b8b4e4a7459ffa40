"""Draws what RoboMW's live Foxglove WebSocket carries, from the messages a client receives: it
connects as Foxglove does (subprotocol foxglove.sdk.v1), subscribes to every channel for a while,
optionally drives a robot by publishing Twists as Foxglove's teleop panel does, and writes an SVG:
the arena from /world/scene (foxglove.SceneUpdate), each robot's trail from /robots/R/pose
(foxglove.PoseInFrame), and every channel with its schema and the messages received on it.
It is a picture of the stream, drawn by this script, not a screenshot of Foxglove.

    python live_picture.py ws://127.0.0.1:8765 out.svg [--seconds 8] [--drive nxt --linear 0.2 --angular 0.6]

Needs websockets (src-it/src/test/python/requirements.txt).
"""
import argparse
import asyncio
import html
import json
import math
import struct
from collections import defaultdict

from websockets.asyncio.client import connect


async def record(a):
    channels, counts, poses, scene = {}, defaultdict(int), defaultdict(list), None
    async with connect(a.url, subprotocols=["foxglove.sdk.v1", "foxglove.websocket.v1"], max_size=None) as ws:
        info = json.loads(await ws.recv())
        loop = asyncio.get_running_loop()
        end = loop.time() + a.seconds
        next_twist = loop.time()
        if a.drive:
            await ws.send(json.dumps({"op": "advertise", "channels": [
                {"id": 1, "topic": f"/robots/{a.drive}/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/Twist"}]}))
        twist = json.dumps({"linear": {"x": a.linear, "y": 0, "z": 0}, "angular": {"x": 0, "y": 0, "z": a.angular}}).encode()
        while loop.time() < end:
            if a.drive and loop.time() >= next_twist:
                await ws.send(struct.pack("<BI", 1, 1) + twist)
                next_twist += 0.1
            try:
                m = await asyncio.wait_for(ws.recv(), 0.05)
            except asyncio.TimeoutError:
                continue
            if isinstance(m, str):
                msg = json.loads(m)
                if msg["op"] == "advertise":
                    new = [c for c in msg["channels"] if c["id"] not in channels]
                    for c in new:
                        channels[c["id"]] = c
                    await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": c["id"], "channelId": c["id"]} for c in new]}))
            elif m[0] == 1:
                _, sub, _ = struct.unpack_from("<BIQ", m)
                c = channels[sub]
                counts[sub] += 1
                payload = json.loads(m[13:])
                if c["topic"] == "/world/scene":
                    scene = payload
                elif c["topic"].startswith("/robots/") and c["topic"].endswith("/pose"):
                    p = payload["pose"]
                    q = p["orientation"]
                    poses[c["topic"].split("/")[2]].append((p["position"]["x"], p["position"]["y"], 2 * math.atan2(q["z"], q["w"])))
    return info, channels, counts, poses, scene


def svg(info, channels, counts, poses, scene, a):
    w, h, map_w = 1200, 620, 660
    cubes = [c for e in (scene or {}).get("entities", []) for c in e["cubes"]]
    xs = [c["pose"]["position"]["x"] + s * c["size"]["x"] / 2 for c in cubes for s in (-1, 1)] or [0, 4]
    ys = [c["pose"]["position"]["y"] + s * c["size"]["y"] / 2 for c in cubes for s in (-1, 1)] or [0, 3]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    k = min((map_w - 60) / (x1 - x0), (h - 140) / (y1 - y0))
    sx = lambda x: 30 + (x - x0) * k
    sy = lambda y: 90 + (y1 - y) * k
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="13">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="30" y="32" font-size="18" font-weight="bold">{html.escape(info["name"])}</text>',
           f'<text x="30" y="56" fill="#555">what its Foxglove WebSocket carried to one client in {a.seconds:g} s '
           f'(subprotocol foxglove.sdk.v1, capabilities {html.escape(json.dumps(info["capabilities"]))}); drawn from the received messages, not a Foxglove screenshot</text>']
    for c in cubes:
        p, s, col = c["pose"]["position"], c["size"], c["color"]
        q = c["pose"]["orientation"]
        ang = -math.degrees(2 * math.atan2(q["z"], q["w"]))
        rgb = f'rgb({int(col["r"] * 255)},{int(col["g"] * 255)},{int(col["b"] * 255)})'
        out.append(f'<rect x="{sx(p["x"]) - s["x"] * k / 2:.1f}" y="{sy(p["y"]) - s["y"] * k / 2:.1f}" width="{s["x"] * k:.1f}" '
                   f'height="{s["y"] * k:.1f}" fill="{rgb}" transform="rotate({ang:.1f} {sx(p["x"]):.1f} {sy(p["y"]):.1f})"/>')
    for e in (scene or {}).get("entities", []):
        for c in e["cylinders"]:
            p, s = c["pose"]["position"], c["size"]
            out.append(f'<circle cx="{sx(p["x"]):.1f}" cy="{sy(p["y"]):.1f}" r="{s["x"] * k / 2:.1f}" fill="rgb(140,150,163)"/>')
    colors = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e"]
    for i, (robot, trail) in enumerate(sorted(poses.items())):
        col = colors[i % len(colors)]
        pts = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y, _ in trail)
        out.append(f'<polyline points="{pts}" fill="none" stroke="{col}" stroke-width="2.5"/>')
        x, y, th = trail[-1]
        out.append(f'<circle cx="{sx(x):.1f}" cy="{sy(y):.1f}" r="7" fill="{col}"/>')
        out.append(f'<line x1="{sx(x):.1f}" y1="{sy(y):.1f}" x2="{sx(x) + 18 * math.cos(th):.1f}" y2="{sy(y) - 18 * math.sin(th):.1f}" stroke="{col}" stroke-width="3"/>')
        label = robot + (" (Twists from this client)" if robot == a.drive else "")
        anchor, dx = ("end", -12) if sx(x) > map_w / 2 else ("start", 12)
        out.append(f'<text x="{sx(x) + dx:.1f}" y="{sy(y) - 12:.1f}" text-anchor="{anchor}" fill="#222">{html.escape(label)}</text>')
    out.append(f'<text x="{map_w + 20}" y="100" font-weight="bold">channel</text><text x="{map_w + 270}" y="100" font-weight="bold">schema</text>'
               f'<text x="{w - 30}" y="100" font-weight="bold" text-anchor="end">messages</text>')
    for row, c in enumerate(sorted(channels.values(), key=lambda c: c["topic"])):
        y = 124 + row * 21
        out.append(f'<text x="{map_w + 20}" y="{y}">{html.escape(c["topic"])}</text><text x="{map_w + 270}" y="{y}" fill="#555">{html.escape(c["schemaName"])}</text>'
                   f'<text x="{w - 30}" y="{y}" text-anchor="end">{counts[c["id"]]}</text>')
    out.append("</svg>")
    return "\n".join(out)


if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("url")
    p.add_argument("out")
    p.add_argument("--seconds", type=float, default=8)
    p.add_argument("--drive")
    p.add_argument("--linear", type=float, default=0.2)
    p.add_argument("--angular", type=float, default=0.6)
    a = p.parse_args()
    result = asyncio.run(record(a))
    with open(a.out, "w") as f:
        f.write(svg(*result, a))
