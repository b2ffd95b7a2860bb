"""rosbag play's time base: playback starts at the first message it plays (rosbag's view begin),
so --topics and -s never make it wait through messages it does not play; the status line counts
Duration from that message, out of the played view's length. Debian's C++ player, when
installed, prints the same Bag Time / Duration for the same bag."""

from __future__ import annotations

import re
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

import rosbag
from tests.support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, ros_env, wait_for_master

BIN = Path(sys.executable).parent
FIRST_STATUS = "Bag Time:    105.000000   Duration: 0.000000 / 0.500000"


@pytest.fixture(scope="module")
def lead_bag(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[dict[str, str], Path]]:
    """A master, and a bag where /a is 5 s ahead of the two /b messages (105.0 and 105.5)."""
    from rospy import Time
    from std_msgs.msg import String

    home = tmp_path_factory.mktemp("play_timing")
    bag = home / "lead.bag"
    with rosbag.Bag(bag, "w") as b:
        b.write("/a", String(data="a"), Time(100, 0))
        b.write("/b", String(data="b0"), Time(105, 0))
        b.write("/b", String(data="b1"), Time(105, 500_000_000))
    port = free_port()
    env = ros_env(home, f"http://127.0.0.1:{port}/")
    core = Proc([str(BIN / "rosmaster"), "--core", "-p", str(port)], env)
    try:
        wait_for_master(env["ROS_MASTER_URI"], proc=core)
        yield env, bag
    finally:
        core.stop()


def _play(env: dict[str, str], command: list[str], *args: str) -> tuple[float, list[str]]:
    start = time.monotonic()
    res = subprocess.run([*command, *args], env=env, capture_output=True, text=True, timeout=30)
    elapsed = time.monotonic() - start
    assert res.returncode == 0, res.stdout + res.stderr
    return elapsed, [line.strip() for line in re.split(r"[\r\n]", res.stdout) if "Bag Time:" in line]


@pytest.mark.parametrize("select", [["--topics", "/b"], ["-s", "1"]], ids=["topics", "start"])
def test_play_starts_at_the_first_message_played(lead_bag: tuple[dict[str, str], Path], select: list[str]) -> None:
    env, bag = lead_bag
    elapsed, status = _play(env, [str(BIN / "rosbag"), "play"], str(bag), *select)
    assert status and FIRST_STATUS in status[0], status
    # 0.2 s of advertise delay and 0.5 s of bag, plus the tool's start-up (1-2 s on a loaded
    # machine); waiting through /a's lead would take 4 s (-s 1) or 5 s more: 4.7 s at the least
    assert elapsed < 4.5, f"{elapsed:.2f} s: playback waited for messages it does not play"


@pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")
def test_debian_rosbag_play_shows_the_same_status(lead_bag: tuple[dict[str, str], Path]) -> None:
    env, bag = lead_bag
    _, status = _play(env, [SYSTEM_PYTHON, "/usr/bin/rosbag", "play"], str(bag), "--topics", "/b")
    assert status and FIRST_STATUS in status[0], status
