"""rospy_tutorials' programs as Noetic ships them, run by rosrun: the service tutorial's
add_two_ints_server and add_two_ints_client (usage, the sum), and each of the others starts."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.turtlesim.sim import Sim, master

PROGRAMS = ["add_two_ints_client", "add_two_ints_server", "listener", "listener.py", "listener_header",
            "listener_subscribe_notify", "listener_with_user_data", "on_shutdown", "param_talker", "talker",
            "talker.py", "talker_header"]


@pytest.fixture(scope="module")
def sim(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    with master(Path(tmp_path_factory.mktemp("rospy_tutorials"))) as graph:
        yield graph


def test_rospy_tutorials_ships_noetics_programs(sim: Sim) -> None:
    listed = sim.run("rosrun", "rospy_tutorials", "add_two_ints_client", "x", check=False)
    assert listed.stdout.endswith("add_two_ints_client [x y]\n"), listed.stdout + listed.stderr
    assert listed.returncode == 1
    found = sim.run("rospack", "find", "rospy_tutorials").stdout.strip()
    scripts = sorted(p.name for p in (Path(found) / "scripts").iterdir() if p.is_file())
    assert scripts == PROGRAMS


def test_add_two_ints_client_and_server(sim: Sim) -> None:
    sim.start("rospy_tutorials", "add_two_ints_server", wait="Ready to add Two Ints")
    asked = sim.run("rosrun", "rospy_tutorials", "add_two_ints_client", "1", "2")
    assert asked.stdout == "Requesting 1+2\n1 + 2 = 3\n"
    assert sim.run("rosservice", "call", "/add_two_ints", "3", "4").stdout == "sum: 7\n"


def test_the_other_tutorial_programs_publish(sim: Sim) -> None:
    sim.start("rospy_tutorials", "talker_header")
    header = sim.run("rostopic", "echo", "-n", "1", "/chatter_header", timeout=20).stdout
    assert "stamp:" in header and "data: \"hello world" in header
    sim.start("rospy_tutorials", "param_talker", "_topic_name:=said")
    assert "data: \"hello: " in sim.run("rostopic", "echo", "-n", "1", "/said", timeout=20).stdout
    assert sim.run("rosparam", "get", "/param_talker/private_bar").stdout == "3\n"
