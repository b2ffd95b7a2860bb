"""A restarted master (beyond ROS 1): running nodes notice and register again, so a turtlesim
started before the master restarts (as `roscore`) is listed again, keeps its parameters, and moves for a
teleop started after the restart (its subscription, which only the new master can tell the
new publisher about) while a new `rostopic echo` sees its pose (its publication)."""

from __future__ import annotations

import time
from pathlib import Path
from urllib.parse import urlsplit

from tests.support import Proc, wait_for_master

from .sim import BIN, turtlesim, wait_until


def test_a_restarted_master_gets_turtlesim_back_and_the_turtle_moves(tmp_path: Path) -> None:
    with turtlesim(tmp_path) as (sim, _):
        assert sim.run("rosparam", "get", "/turtlesim/background_b").stdout.strip() == "255"
        old_master = sim.procs.pop(0)
        old_master.stop()
        new_master = Proc([str(BIN / "roscore"), "-p", str(urlsplit(sim.uri).port)], sim.env)
        sim.procs.insert(0, new_master)
        wait_for_master(sim.uri, proc=new_master)
        restarted = time.monotonic()
        wait_until(lambda: "/turtlesim" in sim.run("rosnode", "list").stdout.split(), what="turtlesim registered")
        back_after = time.monotonic() - restarted
        assert sim.run("rosparam", "get", "/turtlesim/background_b").stdout.strip() == "255"
        start = sim.pose()["x"]
        sim.procs.append(Proc([str(BIN / "rostopic"), "pub", "-r", "20", "/turtle1/cmd_vel", "geometry_msgs/Twist",
                               "{linear: {x: 2.0}}"], sim.env))
        wait_until(lambda: sim.pose()["x"] > start + 1.0, timeout=20, what="the turtle moving")
        print(f"turtlesim listed again {back_after:.2f} s after the new master answered")
