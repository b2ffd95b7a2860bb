"""A restarted master (beyond ROS 1): running nodes notice and register again, so a turtlesim
started before the master restarts (as `roscore`) is listed again within 2 s of the new master
answering, keeps its parameters, answers its services (/spawn), and moves for a teleop started
after the restart (its subscription, which only the new master can tell the new publisher about)
while a new `rostopic echo` sees its pose (its publication)."""

from __future__ import annotations

import time
import xmlrpc.client
from pathlib import Path
from urllib.parse import urlsplit

from tests.support import Proc, wait_for_master

from .sim import BIN, turtlesim, wait_until

# The bound: a node asks the master who it is every 0.5 s (kame.node.master_watch), so
# it is registered again about 0.5 s after the new master answers; 2 s leaves room for a loaded
# 2-core machine's scheduling of the node's threads.
BACK_WITHIN = 2.0


def listed_nodes(uri: str) -> set[str]:
    """The nodes `rosnode list` would list: everyone in the master's getSystemState."""
    publishers, subscribers, services = xmlrpc.client.ServerProxy(uri).getSystemState("/test")[2]
    return {node for entries in (publishers, subscribers, services) for _, nodes in entries for node in nodes}


def test_a_restarted_master_gets_turtlesim_back_and_the_turtle_moves(tmp_path: Path) -> None:
    with turtlesim(tmp_path) as (sim, _):
        assert sim.run("rosparam", "get", "/turtlesim/background_b").stdout.strip() == "255"
        old_master = sim.procs.pop(0)
        old_master.stop()
        new_master = Proc([str(BIN / "roscore"), "-p", str(urlsplit(sim.uri).port)], sim.env)
        sim.procs.insert(0, new_master)
        wait_for_master(sim.uri, proc=new_master)
        # measured from the new master's first answer (wait_for_master asks every 0.05 s) by asking
        # the master in this process: a `rosnode list` run would add its own start-up to the time
        answered = time.monotonic()
        wait_until(lambda: "/turtlesim" in listed_nodes(sim.uri), timeout=20, what="turtlesim registered")
        back_after = time.monotonic() - answered
        print(f"turtlesim listed again {back_after:.2f} s after the new master answered")
        assert back_after <= BACK_WITHIN
        assert "/turtlesim" in sim.run("rosnode", "list").stdout.split()
        assert sim.run("rosparam", "get", "/turtlesim/background_b").stdout.strip() == "255"
        # its services are registered again: a call goes through the new master's lookupService
        sim.run("rosservice", "call", "/spawn", "5.0", "5.0", "0.0", "turtle2")
        assert sim.pose("turtle2")["x"] == 5.0
        start = sim.pose()["x"]
        sim.procs.append(Proc([str(BIN / "rostopic"), "pub", "-r", "20", "/turtle1/cmd_vel", "geometry_msgs/Twist",
                               "{linear: {x: 2.0}}"], sim.env))
        wait_until(lambda: sim.pose()["x"] > start + 1.0, timeout=20, what="the turtle moving")
