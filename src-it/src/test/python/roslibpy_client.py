"""A ROS user's script against RoboMW's rosbridge endpoint, with roslibpy (io.robomw.it.rosbridge.RoslibpyIT).

Usage: python roslibpy_client.py PORT ROBOT RANGE_TOPIC  (the transport from ROSLIBPY_TRANSPORT: twisted or asyncio)

What it checks, as a ROS user would see it: the topics through rosapi, odometry and a range sensor
subscribed to, Twist published on cmd_vel moving the robot and the robot stopping (its watchdog)
once the script stops publishing, a move service, and bad input refused without the connection
dropping. Prints one line per step; exits 1 with the reason on the first thing that is not so.
"""
import logging
import os
import sys
import threading
import time

import roslibpy

PORT, ROBOT, RANGE = int(sys.argv[1]), sys.argv[2], sys.argv[3]
TRANSPORT = os.environ.get("ROSLIBPY_TRANSPORT", "twisted")
WITHIN = 30.0


class Problems(logging.Handler):
    """Collects what roslibpy logs at warning or above: a status, fragment or binary frame it cannot handle shows here."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.records = []

    def emit(self, record):
        self.records.append(record.getMessage())


problems = Problems()
logging.getLogger("roslibpy").addHandler(problems)


def step(text):
    print(f"[{TRANSPORT}] {text}", flush=True)


def fail(text):
    print(f"[{TRANSPORT}] FAIL {text}", flush=True)
    sys.exit(1)


def wait_until(what, condition, within=WITHIN):
    deadline = time.monotonic() + within
    while time.monotonic() < deadline:
        if condition():
            return
        time.sleep(0.02)
    fail(f"not within {within} s: {what}")


class Latest:
    """The messages of one subscription, as they come."""

    def __init__(self):
        self.lock = threading.Lock()
        self.messages = []

    def __call__(self, message):
        with self.lock:
            self.messages.append(message)

    def count(self):
        with self.lock:
            return len(self.messages)

    def last(self):
        with self.lock:
            return self.messages[-1] if self.messages else None


def x_of(odometry):
    return odometry["pose"]["pose"]["position"]["x"]


ros = roslibpy.Ros(host="127.0.0.1", port=PORT)
ros.run(timeout=WITHIN)
step(f"connected to ws://127.0.0.1:{PORT} with roslibpy {roslibpy.__version__}")

# 1. What is there, through rosapi, as every client asks first.
topics = ros.get_topics()
for t in (f"/{ROBOT}/odom", f"/{ROBOT}/cmd_vel", RANGE, "/tf", "/tf_static"):
    if t not in topics:
        fail(f"{t} is not among the topics {topics}")
if ros.get_topic_type(f"/{ROBOT}/odom") != "nav_msgs/msg/Odometry":
    fail(f"/{ROBOT}/odom has type {ros.get_topic_type(f'/{ROBOT}/odom')}")
services = ros.get_services()
if f"/{ROBOT}/move" not in services or "/rosapi/topics" not in services:
    fail(f"services are {services}")
if f"/{ROBOT}" not in ros.get_nodes():
    fail(f"nodes are {ros.get_nodes()}")
step(f"rosapi: {len(topics)} topics, {len(services)} services, odometry nav_msgs/msg/Odometry")

# 2. Odometry and range, subscribed to.
odometry = Latest()
odom_topic = roslibpy.Topic(ros, f"/{ROBOT}/odom", "nav_msgs/msg/Odometry")
odom_topic.subscribe(odometry)
ranges = Latest()
range_topic = roslibpy.Topic(ros, RANGE, "sensor_msgs/Range")  # the short spelling works too
range_topic.subscribe(ranges)
wait_until("odometry and range messages", lambda: odometry.count() >= 5 and ranges.count() >= 2)
first = odometry.last()
if first["header"]["frame_id"] != f"{ROBOT}/odom" or first["child_frame_id"] != f"{ROBOT}/base_link":
    fail(f"odometry frames are {first['header']['frame_id']} -> {first['child_frame_id']}")
stamp = first["header"]["stamp"]
if set(stamp) != {"sec", "nanosec"} or abs(stamp["sec"] - time.time()) > 60:
    fail(f"the stamp is {stamp}, not ROS 2 time now")
r = ranges.last()
if not (r["min_range"] <= r["range"] <= r["max_range"]) or r["radiation_type"] not in (0, 1):
    fail(f"a range message is {r}")
step(f"odometry at x={x_of(first):.3f} in {ROBOT}/odom; range {r['range']:.3f} m (limits {r['min_range']:.2f}-{r['max_range']:.2f})")

# 3. Twist on cmd_vel drives it; the robot's watchdog stops it when the script stops publishing.
x0 = x_of(odometry.last())
cmd_vel = roslibpy.Topic(ros, f"/{ROBOT}/cmd_vel", "geometry_msgs/msg/Twist")
twist = roslibpy.Message({"linear": {"x": 0.1, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}})
until = time.monotonic() + 2.0
while time.monotonic() < until:
    cmd_vel.publish(twist)
    time.sleep(0.1)
wait_until("odometry showing the robot drove forward", lambda: x_of(odometry.last()) > x0 + 0.05)
step(f"published Twist 0.1 m/s for 2 s: x {x0:.3f} -> {x_of(odometry.last()):.3f}")
stopped_at = None


def stopped():
    global stopped_at
    last = odometry.last()
    if last["twist"]["twist"]["linear"]["x"] == 0.0:
        stopped_at = x_of(last)
        return True
    return False


wait_until("the robot stopping once the script stopped publishing (its watchdog)", stopped)
count = odometry.count()
wait_until("a second of odometry after it stopped", lambda: odometry.count() >= count + 5)
if abs(x_of(odometry.last()) - stopped_at) > 0.002:
    fail(f"the robot went on after it stopped: {stopped_at:.3f} -> {x_of(odometry.last()):.3f}")
step(f"stopped by its watchdog at x={stopped_at:.3f}, and stays there")
cmd_vel.unadvertise()

# 4. A move service, answered once the robot has moved.
move = roslibpy.Service(ros, f"/{ROBOT}/move", "robomw_msgs/srv/Move")
before = x_of(odometry.last())
answer = move.call(roslibpy.ServiceRequest({"distance": 0.1, "speed": 0.1}), timeout=WITHIN)
if not answer["success"]:
    fail(f"move answered {answer}")
wait_until("odometry after the move", lambda: abs(x_of(odometry.last()) - (before + 0.1)) < 0.03)
step(f"/{ROBOT}/move 0.1 m: {answer['message']}; x {before:.3f} -> {x_of(odometry.last()):.3f}")

# 5. Bad input: refused cleanly, the connection goes on.
try:
    move.call(roslibpy.ServiceRequest({"distance": "far", "speed": 0.1}), timeout=WITHIN)
    fail("a move with distance 'far' was answered as if it were fine")
except roslibpy.core.ServiceException as e:
    if "requires a float64 for field distance" not in str(e):
        fail(f"the refusal says {e}")
    step(f"move with distance 'far' refused: {e}")
try:
    roslibpy.Service(ros, "/no/such/service", "std_srvs/srv/Trigger").call(roslibpy.ServiceRequest({}), timeout=WITHIN)
    fail("a call to a service that does not exist was answered")
except roslibpy.core.ServiceException as e:
    step(f"unknown service refused: {e}")
refusal = move.call(roslibpy.ServiceRequest({"distance": 0.1, "speed": 50.0}), timeout=WITHIN)
if refusal["success"] or "50.000" not in refusal["message"]:  # refused at once here, or failed by the host that serves the robot
    fail(f"a move at 50 m/s answered {refusal}")
step(f"move at 50 m/s: success false, {refusal['message']}")
ros.factory.on_ready(lambda proto: proto.send_message(b"{this is not json"))
ros.send_on_ready(roslibpy.Message({"op": "no_such_op", "id": "x"}))
roslibpy.Topic(ros, f"/{ROBOT}/cmd_vel", "geometry_msgs/msg/Twist").publish(roslibpy.Message({"linear": "fast"}))
if ros.get_topic_type(f"/{ROBOT}/odom") != "nav_msgs/msg/Odometry" or not ros.is_connected:
    fail("the connection did not go on after bad input")
time.sleep(0.5)  # any status frame the bridge wrongly sent would have come by now
if problems.records:
    fail(f"roslibpy logged problems (a frame it cannot handle?): {problems.records}")
step("bad JSON, an unknown op and a malformed Twist: no reply roslibpy cannot handle, and the connection goes on")

odom_topic.unsubscribe()
range_topic.unsubscribe()
ros.terminate() if TRANSPORT == "twisted" else ros.close()
step("PASS")
