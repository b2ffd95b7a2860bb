"""turtlebot_rviz_launchers: view_robot.launch and view_navigation.launch start rviz on their
shipped .rviz files; the files load in kame's rviz with every display known; on a running
turtlebot_world.launch the robot, its scan and its odometry show in the window with status Ok and
the scan's points drawn, and with amcl_demo.launch too the navigation file's map, costmap and
particle cloud do; on the 3-D world the robot is drawn in its URDF's colours, readable (no frame
names over it, one odometry arrow). The windows run on a private Xvfb."""

from __future__ import annotations

import importlib.util
import math
import sys
import time
from pathlib import Path
from typing import Any

import pytest

import kame
from kame.rviz import config
from tests.stage.sim import echo
from tests.support import REPO, Proc
from tests.support.tour import shoot
from tests.turtlesim.sim import BIN, master, wait_until

PACKAGE = Path(kame.__file__).parent / "share" / "turtlebot_rviz_launchers"
BACKGROUND = (48, 48, 48)  # robot.rviz's Background Color


def _displays(path: Path) -> dict[str, tuple[str, str]]:
    loaded = config.load(str(path))
    assert loaded.unknown_displays == [], loaded.unknown_displays
    return {d.name: (d.class_name, d.topic) for d in loaded.displays}


def test_the_shipped_configs_load_with_every_display_known() -> None:
    robot = config.load(str(PACKAGE / "rviz" / "robot.rviz"))
    assert robot.fixed_frame == "odom"
    assert _displays(PACKAGE / "rviz" / "robot.rviz") == {
        "Grid": ("rviz/Grid", ""), "RobotModel": ("rviz/RobotModel", ""), "TF": ("rviz/TF", ""),
        "LaserScan": ("rviz/LaserScan", "/scan"), "Odometry": ("rviz/Odometry", "/odom")}
    navigation = config.load(str(PACKAGE / "rviz" / "navigation.rviz"))
    assert navigation.fixed_frame == "map"
    shown = _displays(PACKAGE / "rviz" / "navigation.rviz")
    assert {topic for _, topic in shown.values()} >= {
        "/map", "/scan", "/particlecloud", "/move_base/global_costmap/costmap", "/move_base/NavfnROS/plan",
        "/move_base/local_costmap/costmap", "/move_base/DWAPlannerROS/local_plan"}
    assert shown["Amcl Particles"][0] == "rviz/PoseArray" and shown["RobotModel"][0] == "rviz/RobotModel"
    tools = {tool["Class"]: tool.get("Topic") for tool in navigation.raw["Visualization Manager"]["Tools"]}
    assert tools["rviz/SetInitialPose"] == "/initialpose" and tools["rviz/SetGoal"] == "/move_base_simple/goal"
    for launch in ("view_robot.launch", "view_navigation.launch"):
        text = (PACKAGE / "launch" / launch).read_text()
        assert 'pkg="rviz" type="rviz"' in text and "$(find turtlebot_rviz_launchers)/rviz/" in text


def _statuses(line: str) -> dict[str, str]:
    listed = line.split(" status ", 1)[1].split(" colour ")[0]
    return dict(entry.rsplit(":", 1) for entry in listed.split(";"))


def test_view_robot_shows_the_turtlebot_world(tmp_path: Path) -> None:
    pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
    pytest.importorskip("PySide6")
    pytest.importorskip("numpy", reason="the 2-D world needs kame[sim]")
    from tests.turtlesim.xserver import xvfb

    with master(tmp_path) as sim, xvfb("1600x1000") as display:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", "simulator:=stage"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=60)
        windowed = dict(sim.env, DISPLAY=display)
        windowed.pop("QT_QPA_PLATFORM", None)
        launched = Proc([str(BIN / "roslaunch"), "turtlebot_rviz_launchers", "view_robot.launch"], windowed,
                        cwd=sim.home)
        sim.procs.append(launched)

        def rviz_subscribes() -> bool:
            info = sim.run("rostopic", "info", "/odom", check=False).stdout
            return " * /rviz (" in info.split("Subscribers:", 1)[-1]  # the launch file's name="rviz"

        wait_until(rviz_subscribes, timeout=90, what="view_robot's rviz to subscribe to /odom")
        assert " * /rviz (" in sim.run("rostopic", "info", "/scan").stdout.split("Subscribers:", 1)[-1]

        # the same file in a window the test can read: each display's status and the scan's pixels (in a
        # colour of its own here: the shipped red is also the TF axes' x), with the TF display on (off as
        # shipped, as upstream's) to find base_link's label
        shipped = (PACKAGE / "rviz" / "robot.rviz").read_text()
        scan_colour = "      Color: 255; 0; 0\n      Color Transformer: FlatColor\n"
        tf_off = "    - Class: rviz/TF\n      Enabled: false\n"
        assert scan_colour in shipped and tf_off in shipped
        readable = tmp_path / "robot.rviz"
        readable.write_text(shipped.replace(scan_colour, scan_colour.replace("255; 0; 0", "10; 200; 240"))
                            .replace(tf_off, tf_off.replace("false", "true")))
        rviz = Proc([sys.executable, "-m", "tests.rviz.live_child", sim.uri, str(readable),
                     "base_link", "--colour", "10,200,240"], windowed, cwd=REPO)
        sim.procs.append(rviz)
        line = ""
        deadline = time.monotonic() + 90
        while time.monotonic() < deadline:
            reports = [line for line in list(rviz.out) if line.startswith("frames ")]
            line = reports[-1] if reports else ""
            if line and set(_statuses(line).values()) == {"Ok"} and int(line.split(" colour ")[1]) > 20:
                break
            time.sleep(0.2)
        assert line, f"no report from rviz:\n{''.join(rviz.out)}\n{''.join(rviz.err)}"
        statuses = _statuses(line)
        assert statuses == {"Grid": "Ok", "RobotModel": "Ok", "TF": "Ok", "LaserScan": "Ok", "Odometry": "Ok"}, line
        assert int(line.split(" colour ")[1]) > 20, line  # the scan's points drawn
        assert "base_link=" in line and "base_link=none" not in line
        shoot(display, "robot.rviz - RViz", "rviz_view_robot")  # the tour (tests/support/tour.py)


def test_view_navigation_shows_amcl_demo(tmp_path: Path) -> None:
    pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
    pytest.importorskip("PySide6")
    pytest.importorskip("numpy", reason="the 2-D world needs kame[sim]")
    from tests.turtlesim.xserver import xvfb

    with master(tmp_path) as sim, xvfb("1600x1000") as display:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", "simulator:=stage"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=60)
        sim.procs.append(Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "amcl_demo.launch"], sim.env, cwd=sim.home))
        windowed = dict(sim.env, DISPLAY=display)
        windowed.pop("QT_QPA_PLATFORM", None)
        launched = Proc([str(BIN / "roslaunch"), "turtlebot_rviz_launchers", "view_navigation.launch"], windowed,
                        cwd=sim.home)
        sim.procs.append(launched)
        # the launched window's node subscribes to every display's topic of the navigation file
        topics = {topic for _, topic in _displays(PACKAGE / "rviz" / "navigation.rviz").values() if topic}
        subscribed: set[str] = set()

        def rviz_subscribes() -> bool:
            info = sim.run("rosnode", "info", "/rviz", check=False).stdout  # the launch file's name="rviz"
            listed = info.split("Subscriptions:", 1)[-1].split("Services:", 1)[0]
            subscribed.update(line.split()[1] for line in listed.splitlines() if line.startswith(" * "))
            return subscribed >= topics

        wait_until(rviz_subscribes, timeout=90, what=f"view_navigation's rviz to subscribe to {sorted(topics)}")

        # the same file in a window the test can read: each display's status
        rviz = Proc([sys.executable, "-m", "tests.rviz.live_child", sim.uri, str(PACKAGE / "rviz" / "navigation.rviz"),
                     "base_link"], windowed, cwd=REPO)
        sim.procs.append(rviz)
        wanted = ("Grid", "RobotModel", "LaserScan", "Map", "Global Costmap", "Local Costmap", "Amcl Particles")
        line = ""
        deadline = time.monotonic() + 70
        while time.monotonic() < deadline:
            reports = [line for line in list(rviz.out) if line.startswith("frames ")]
            line = reports[-1] if reports else ""
            if line and all(_statuses(line)[name] == "Ok" for name in wanted):
                break
            time.sleep(0.2)
        assert line, f"no report from rviz:\n{''.join(rviz.out)}\n{''.join(rviz.err)}"
        assert {name: _statuses(line)[name] for name in wanted} == dict.fromkeys(wanted, "Ok"), line
        shoot(display, "navigation.rviz - RViz", "rviz_view_navigation")  # the tour (tests/support/tour.py)


def _around_the_robot(shot: Any, plate: tuple[int, int, int] = (197, 197, 197), reach: int = 90) -> dict[str, int]:
    """In the 3-D view (right of the Displays panel: from the first run of its background colour
    across the middle row), pixels of the robot's white plates (lit), and within `reach` of their
    middle the red of arrows and the near-white of text."""
    step = 2
    middle = shot.height // 2
    left = next(x for x in range(shot.width - 20) if all(shot.rgb(x + i, middle) == BACKGROUND for i in range(20)))
    plates = [(x, y) for y in range(0, shot.height, step) for x in range(left, shot.width, step)
              if all(abs(c - p) <= 4 for c, p in zip(shot.rgb(x, y), plate, strict=True))]
    if not plates:
        return {"plate": 0, "red": 0, "text": 0}
    cx, cy = sum(x for x, _ in plates) // len(plates), sum(y for _, y in plates) // len(plates)
    red = text = 0
    for y in range(max(cy - reach, 0), min(cy + reach, shot.height), step):
        for x in range(max(cx - reach, 0), min(cx + reach, shot.width), step):
            r, g, b = shot.rgb(x, y)
            red += r > 150 and g < 80 and b < 80
            text += min(r, g, b) > 225
    return {"plate": len(plates), "red": red, "text": text}


def test_view_robot_on_the_3d_world_shows_the_turtlebot_readably(tmp_path: Path) -> None:
    # as turtlebot_rviz_launchers' robot.rviz: its TF display off (rviz's TF display names every
    # frame, and the Kobuki's 30 print over each other on the robot), and the odometry's arrow is
    # the newest pose only (a turn in place left 100 red arrows around the robot)
    pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
    pytest.importorskip("PySide6")
    if importlib.util.find_spec("mujoco") is None:  # looked up: importing it would fix PyOpenGL's platform here
        pytest.skip("kame[gazebo] (MuJoCo) is not installed")
    from tests.turtlesim.xserver import xvfb

    with master(tmp_path) as sim, xvfb("1200x850") as display:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", "gui:=false"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Advertise odom on odom", timeout=90)
        windowed = dict(sim.env, DISPLAY=display)
        windowed.pop("QT_QPA_PLATFORM", None)
        sim.procs.append(Proc([str(BIN / "roslaunch"), "turtlebot_rviz_launchers", "view_robot.launch"], windowed,
                              cwd=sim.home))

        def rviz_subscribes() -> bool:
            info = sim.run("rostopic", "info", "/odom", check=False).stdout
            return " * /rviz (" in info.split("Subscribers:", 1)[-1]

        wait_until(rviz_subscribes, timeout=90, what="view_robot's rviz to subscribe to /odom")
        turning = Proc([str(BIN / "rostopic"), "pub", "-r", "10", "/cmd_vel", "geometry_msgs/Twist",
                        "{angular: {z: 1.0}}"], sim.env, cwd=sim.home)
        sim.procs.append(turning)

        def heading() -> float:
            q = echo(sim, "/odom")["pose"]["pose"]["orientation"]
            return math.atan2(2 * (q["w"] * q["z"] + q["x"] * q["y"]), 1 - 2 * (q["y"] ** 2 + q["z"] ** 2))

        # from facing +x, anticlockwise past pi to -1.2 rad: 5 rad turned, 50 odometry poses 0.1 rad apart
        wait_until(lambda: -2.0 < heading() < -1.2, timeout=60, what="the Kobuki to turn most of a circle")
        turning.stop()
        seen: dict[str, int] = {}

        def drawn(shot: Any) -> bool:
            seen.update(_around_the_robot(shot))
            return seen["plate"] > 150

        shot = shoot(display, "robot.rviz - RViz", "rviz_view_robot_3d", ready=drawn)
        found = _around_the_robot(shot)
        assert found["plate"] > 150, found  # the hexagon plates in the URDF's white, as lit
        assert found["text"] < 20, found  # no frame names
        assert found["red"] < 300, found  # one odometry arrow (the 100 kept before covered the robot in red)
