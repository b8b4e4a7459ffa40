"""Writes robomw-layout.json, the Foxglove layout for a RoboMW run, live (mw sim/host/demo/console
--foxglove) or recorded (--record, mw record), with foxglove-sdk's own layout model
(foxglove.layouts, foxglove-sdk 0.30.3), so the file is in the shape Foxglove imports.

    python make_layout.py [robomw-layout.json]

Panels: 3D (the arena from /world/scene, robots' frames from /tf, their poses as arrows), a plot
of the range sensors, a plot of true against odometry x, the agents' log, Raw Messages on the
NXT's commands, and a Teleop pad publishing geometry_msgs/Twist on /robots/nxt/cmd_vel (live only:
a recording takes no input). The robot names are those of examples/worlds/arena.yaml (nxt, ft,
aibo); change them in Foxglove's panel settings for other worlds.
"""
import sys

import foxglove.layouts as fl

ROBOTS = {"nxt": "#d62728", "ft": "#1f77b4", "aibo": "#2ca02c"}


def layout():
    three_d = fl.ThreeDeePanel(title="arena", config=fl.ThreeDeeConfig(
        follow_tf="world", fixed_frame="world", follow_mode="follow-none",
        topics={"/world/scene": fl.BaseRendererSceneUpdateTopicSettings(visible=True)}
        | {f"/robots/{r}/pose": fl.BaseRendererPoseTopicSettings(visible=True, type="arrow", color=c) for r, c in ROBOTS.items()}))
    ranges = fl.PlotPanel(title="range sensors (m)", config=fl.PlotConfig(paths=[
        fl.PlotSeries(value="/robots/nxt/sensors/sonar.value"),
        fl.PlotSeries(value="/robots/ft/sensors/range.value")], show_legend=True))
    drift = fl.PlotPanel(title="nxt x: true pose against its odometry (m)", config=fl.PlotConfig(paths=[
        fl.PlotSeries(value="/robots/nxt/pose.pose.position.x"),
        fl.PlotSeries(value="/robots/nxt/odometry.pose.position.x")], show_legend=True))
    log = fl.LogPanel(title="agents", config=fl.LogConfig(topic_to_render="/agents/log"))
    commands = fl.RawMessagesPanel(title="nxt commands", config=fl.RawMessagesConfig(topic_path="/robots/nxt/commands"))
    teleop = fl.TeleopPanel(title="drive nxt (live)", config=fl.TeleopConfig(
        topic="/robots/nxt/cmd_vel", publish_rate=10,
        up_button=fl.TeleopButton(field="linear-x", value=0.2), down_button=fl.TeleopButton(field="linear-x", value=-0.2),
        left_button=fl.TeleopButton(field="angular-z", value=1.0), right_button=fl.TeleopButton(field="angular-z", value=-1.0)))
    right = fl.SplitContainer(direction="column", items=[
        fl.SplitItem(proportion=1, content=ranges), fl.SplitItem(proportion=1, content=drift), fl.SplitItem(proportion=1, content=log)])
    bottom = fl.SplitContainer(direction="row", items=[fl.SplitItem(proportion=2, content=commands), fl.SplitItem(proportion=1, content=teleop)])
    left = fl.SplitContainer(direction="column", items=[fl.SplitItem(proportion=3, content=three_d), fl.SplitItem(proportion=1, content=bottom)])
    return fl.Layout(content=fl.SplitContainer(direction="row", items=[fl.SplitItem(proportion=3, content=left), fl.SplitItem(proportion=2, content=right)]))


if __name__ == "__main__":
    with open(sys.argv[1] if len(sys.argv) > 1 else "robomw-layout.json", "w") as f:
        f.write(layout().to_json())
        f.write("\n")
