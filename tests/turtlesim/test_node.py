"""turtlesim_node end to end, headless, driven with kame's tools as the tutorials type them."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.turtlesim.sim import Sim, master, turtlesim, wait_until

CENTRE = 5.544444561004639


@pytest.fixture(scope="module")
def sim(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    with turtlesim(tmp_path_factory.mktemp("turtlesim")) as (live, node):
        live.node = node  # type: ignore[attr-defined]
        yield live


def log(sim: Sim) -> str:
    node = sim.node  # type: ignore[attr-defined]
    return "".join(node.out) + "".join(node.err)


def test_start_up_graph_and_params(sim: Sim) -> None:
    out = "".join(sim.node.out)  # type: ignore[attr-defined]
    # roscpp's lines, wrapped in INFO's colour (the reset code) also when not on a terminal
    assert "]: Starting turtlesim with node name /turtlesim\033[0m\n" in out
    assert "]: Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]\033[0m\n" in out
    assert out.startswith("\033[0m[ INFO] [")
    assert out.count("runs headless") + out.count("runs without a window") == 1
    topics = sim.run("rostopic", "list").stdout.split()
    assert {"/turtle1/cmd_vel", "/turtle1/pose", "/turtle1/color_sensor"} <= set(topics)
    services = sim.run("rosservice", "list").stdout.split()
    assert {"/clear", "/kill", "/reset", "/spawn", "/turtle1/set_pen", "/turtle1/teleport_absolute",
            "/turtle1/teleport_relative", "/turtlesim/get_loggers"} <= set(services)
    assert sim.run("rosparam", "get", "/turtlesim/background_b").stdout.strip() == "255"
    assert sim.run("rostopic", "type", "/turtle1/cmd_vel").stdout.strip() == "geometry_msgs/Twist"


def test_tutorial_arc(sim: Sim) -> None:
    sim.run("rosservice", "call", "/reset")
    pose = sim.pose()
    assert (pose["x"], pose["y"], pose["theta"]) == (CENTRE, CENTRE, 0.0)
    sim.run("rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--", "[2,0,0]", "[0,0,2]")
    wait_until(lambda: sim.pose()["linear_velocity"] == 0.0, what="the 1 s command timeout")
    pose = sim.pose()
    # 63 steps of 16 ms at v=2, w=2 (the timeout is counted in simulated steps, so exactly 63)
    x = y = CENTRE
    theta = 0.0
    for _ in range(63):
        theta += 0.032
        x += math.cos(theta) * 0.032
        y += math.sin(theta) * 0.032
    assert pose["theta"] == pytest.approx(2.016, abs=1e-6)
    assert (pose["x"], pose["y"]) == pytest.approx((x, y), abs=1e-5)
    assert (pose["x"], pose["y"]) == pytest.approx((6.4240, 6.9894), abs=1e-4)


def test_spawn_kill_and_their_errors(sim: Sim) -> None:
    sim.run("rosservice", "call", "/reset")
    assert sim.run("rosservice", "call", "/spawn", "2", "2", "0.2", '""').stdout.strip() == 'name: "turtle2"'
    assert "]: Spawning turtle [turtle2] at x=[2.000000], y=[2.000000], theta=[0.200000]" in log(sim)
    pose = sim.pose("turtle2")
    assert (pose["x"], pose["y"], pose["theta"]) == pytest.approx((2.0, 2.0, 0.2), abs=1e-6)
    taken = sim.run("rosservice", "call", "/spawn", "3", "3", "0", "turtle2", check=False)
    assert taken.returncode != 0 and "ERROR: service [/spawn] responded with an error" in taken.stderr
    wait_until(lambda: "[ERROR] [" in log(sim) and "A turtled named [turtle2] already exists" in log(sim))
    sim.run("rosservice", "call", "/kill", "turtle2")
    wait_until(lambda: "/turtle2/set_pen" not in sim.run("rosservice", "list").stdout, what="turtle2's services")
    assert "/turtle2/pose" not in sim.run("rostopic", "list").stdout
    unknown = sim.run("rosservice", "call", "/kill", "nobody", check=False)
    assert unknown.returncode != 0 and "responded with an error" in unknown.stderr
    wait_until(lambda: "Tried to kill turtle [nobody], which does not exist" in log(sim))
    # the counter goes on from where it was; reset restarts it
    assert sim.run("rosservice", "call", "/spawn", "4", "4", "0", '""').stdout.strip() == 'name: "turtle3"'
    sim.run("rosservice", "call", "/reset")
    assert "]: Resetting turtlesim." in log(sim)
    wait_until(lambda: "/turtle3/pose" not in sim.run("rostopic", "list").stdout, what="turtle3 to go")


def test_pen_teleports_colour_sensor_and_background(sim: Sim) -> None:
    sim.run("rosservice", "call", "/reset")
    assert sim.echo("/turtle1/color_sensor") == {"r": 69, "g": 86, "b": 255}
    sim.run("rosservice", "call", "/turtle1/set_pen", "255", "0", "0", "5", "0")
    sim.run("rosservice", "call", "/turtle1/teleport_absolute", "1", "1", "0")
    pose = sim.pose()
    assert (pose["x"], pose["y"], pose["theta"]) == (1.0, 1.0, 0.0)
    assert sim.echo("/turtle1/color_sensor") == {"r": 255, "g": 0, "b": 0}  # on its own red line
    sim.run("rosservice", "call", "/turtle1/teleport_relative", "2", "1.5707963")
    pose = sim.pose()
    assert (pose["x"], pose["y"], pose["theta"]) == pytest.approx((1.0, 3.0, 1.5707963), abs=1e-5)
    sim.run("rosservice", "call", "/turtle1/set_pen", "0", "0", "0", "0", "1")  # pen up
    sim.run("rosservice", "call", "/turtle1/teleport_absolute", "9", "9", "0")
    assert sim.echo("/turtle1/color_sensor") == {"r": 69, "g": 86, "b": 255}
    sim.run("rosservice", "call", "/turtle1/teleport_absolute", "1", "2", "0")
    assert sim.echo("/turtle1/color_sensor") == {"r": 255, "g": 0, "b": 0}  # the trail is still there
    assert sim.run("rosservice", "call", "/clear").stdout == "\n"
    assert "]: Clearing turtlesim." in log(sim)
    assert sim.echo("/turtle1/color_sensor") == {"r": 69, "g": 86, "b": 255}
    # the old tutorials' global param, then Noetic's private one
    sim.run("rosparam", "set", "/background_r", "150")
    sim.run("rosservice", "call", "/clear")
    assert sim.echo("/turtle1/color_sensor") == {"r": 150, "g": 86, "b": 255}
    sim.run("rosparam", "set", "/turtlesim/background_g", "0")
    sim.run("rosservice", "call", "/clear")
    assert sim.echo("/turtle1/color_sensor") == {"r": 150, "g": 0, "b": 255}
    sim.run("rosparam", "delete", "/background_r")
    sim.run("rosparam", "set", "/turtlesim/background_g", "86")
    sim.run("rosservice", "call", "/clear")


def test_wall_warning_and_bad_commands(sim: Sim) -> None:
    sim.run("rosservice", "call", "/reset")
    sim.run("rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--", "[20,0,0]", "[0,0,0]")
    # pub -1 latches for 3 s: turtlesim may connect late in that window on a loaded machine
    wait_until(lambda: sim.pose()["x"] == pytest.approx(11.088889, abs=1e-5), what="the turtle at the wall")
    assert "]: Oh no! I hit the wall! (Clamping from [x=11.408889, y=5.544444])\033[0m\n" in log(sim)
    assert "[ WARN] [" in log(sim)  # the window-frame y: 11.088889 - 5.544445
    sim.run("rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--", "[.nan,0,0]", "[0,0,0]")
    wait_until(lambda: "Ignoring a cmd_vel for [turtle1]" in log(sim))
    bad = sim.run("rosservice", "call", "/turtle1/teleport_absolute", "--", "1", ".inf", "0", check=False)
    assert bad.returncode != 0
    pose = sim.pose()
    assert math.isfinite(pose["x"]) and math.isfinite(pose["y"])
    assert sim.node.popen.poll() is None  # type: ignore[attr-defined]


def test_several_simulators_at_once(tmp_path: Path) -> None:
    with master(tmp_path) as live:
        a = live.start("turtlesim", "turtlesim_node", "--headless", "__name:=A", wait="runs without a window")
        live.start("turtlesim", "turtlesim_node", "--headless", "__ns:=two", "__name:=sim",
                   wait="runs without a window")
        assert "Starting turtlesim with node name /A" in "".join(a.out)
        nodes = live.run("rosnode", "list").stdout.split()
        assert {"/A", "/two/sim"} <= set(nodes)
        assert live.run("rosparam", "get", "/A/background_r").stdout.strip() == "69"
        assert live.run("rosparam", "get", "/two/sim/background_r").stdout.strip() == "69"
        live.run("rostopic", "pub", "-1", "/two/turtle1/cmd_vel", "geometry_msgs/Twist", "--", "[1,0,0]", "[0,0,0]")
        wait_until(lambda: live.echo("/two/turtle1/pose")["x"] > CENTRE + 0.9, what="/two's turtle to move 1 m")
        assert live.echo("/turtle1/pose")["x"] == CENTRE


def test_a_turtle_has_ros1s_topics_and_services_and_no_action(sim: Sim) -> None:
    # ROS 1's turtlesim: no rotate_absolute action (that is ROS 2's turtlesim), so `rostopic
    # list` in the teleop lesson shows the course's topics and rosnode info no unknown types
    sim.run("rosservice", "call", "/reset")
    topics = [t for t in sim.run("rostopic", "list").stdout.split() if t.startswith("/turtle1/")]
    assert topics == ["/turtle1/cmd_vel", "/turtle1/color_sensor", "/turtle1/pose"]
    services = [s for s in sim.run("rosservice", "list").stdout.split() if s.startswith("/turtle1/")]
    assert services == ["/turtle1/set_pen", "/turtle1/teleport_absolute", "/turtle1/teleport_relative"]
