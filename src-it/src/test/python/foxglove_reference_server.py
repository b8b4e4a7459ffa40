"""foxglove-sdk's own WebSocket server (the reference implementation), serving a tiny robot for the
probe: a JSON channel TOPIC of foxglove.PoseInFrame poses at 20 Hz, and client publishing, whose
Twists (on any client channel) move the robot. RoboMW's integration tests run foxglove_probe.py
against it and against RoboMW in the same test.

    python foxglove_reference_server.py TOPIC SCHEMA.json

Prints "listening on PORT" (a free port on 127.0.0.1) and serves until its standard input closes.
"""
import json
import math
import sys
import threading
import time

import foxglove
from foxglove.websocket import Capability, ServerListener


class Robot(ServerListener):
    def __init__(self):
        self.x, self.y, self.heading = 0.5, 0.5, 0.0
        self.linear, self.angular = 0.0, 0.0
        self.lock = threading.Lock()

    def on_message_data(self, client, client_channel, data):
        twist = json.loads(data)
        with self.lock:
            self.linear, self.angular = twist["linear"]["x"], twist["angular"]["z"]

    def on_client_unadvertise(self, client, client_channel_id):
        with self.lock:
            self.linear, self.angular = 0.0, 0.0


def main(topic, schema_file):
    with open(schema_file, "rb") as f:
        schema = foxglove.Schema(name="foxglove.PoseInFrame", encoding="jsonschema", data=f.read())
    robot = Robot()
    server = foxglove.start_server(name="reference", host="127.0.0.1", port=0, capabilities=[Capability.ClientPublish],
                                   supported_encodings=["json"], server_listener=robot)
    channel = foxglove.Channel(topic, schema=schema, message_encoding="json")
    print("listening on", server.port, flush=True)
    stop = threading.Event()
    threading.Thread(target=lambda: (sys.stdin.read(), stop.set()), daemon=True).start()
    dt = 0.05
    while not stop.wait(dt):
        with robot.lock:
            robot.heading += robot.angular * dt
            robot.x += robot.linear * dt * math.cos(robot.heading)
            robot.y += robot.linear * dt * math.sin(robot.heading)
            x, y, h = robot.x, robot.y, robot.heading
        now = time.time_ns()
        channel.log({"timestamp": {"sec": now // 1_000_000_000, "nsec": now % 1_000_000_000}, "frame_id": "world",
                     "pose": {"position": {"x": x, "y": y, "z": 0},
                              "orientation": {"x": 0, "y": 0, "z": math.sin(h / 2), "w": math.cos(h / 2)}}}, log_time=now)
    server.stop()


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
