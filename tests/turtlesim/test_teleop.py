"""turtle_teleop_key in a real terminal: tmux types the arrow keys, the turtle moves, `q` quits
and the terminal is as it was. Skipped without tmux."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
from pathlib import Path

import pytest

from kame.turtlesim.teleop_key import twist_for
from tests.support import sending_to
from tests.turtlesim.sim import BIN, turtlesim, wait_until

CENTRE = 5.544444561004639


def test_keys_map_to_the_real_speeds() -> None:
    up, down, left, right = (twist_for(ord(k), 2.0, 2.0) for k in "ABDC")
    assert up is not None and (up.linear.x, up.angular.z) == (2.0, 0.0)
    assert down is not None and down.linear.x == -2.0
    assert left is not None and left.angular.z == 2.0
    assert right is not None and right.angular.z == -2.0
    assert twist_for(0x1B, 2.0, 2.0) is None and twist_for(ord("["), 2.0, 2.0) is None


@pytest.mark.skipif(shutil.which("tmux") is None, reason="tmux is not installed")
def test_arrow_keys_through_tmux(tmp_path: Path) -> None:
    with turtlesim(tmp_path) as (sim, _node):
        sock = str(tmp_path / "tmux.sock")
        stty = tmp_path / "stty.txt"
        script = (f"stty -a > {tmp_path}/before.txt; {BIN}/rosrun turtlesim turtle_teleop_key; "
                  f"stty -a > {stty}.part; mv {stty}.part {stty}; exec sleep 60")  # whole once it exists

        def tmux(*args: str) -> str:
            return subprocess.run(["tmux", "-S", sock, *args], env=sim.env, capture_output=True, text=True,
                                  timeout=10, check=True).stdout

        tmux("new-session", "-d", "-x", "100", "-y", "30", "sh", "-c", script)
        pids = [int(tmux("display", "-p", "#{pid}").strip()), int(tmux("display", "-p", "#{pane_pid}").strip())]
        try:
            wait_until(lambda: "Use arrow keys to move the turtle. 'q' to quit." in tmux("capture-pane", "-p"),
                       what="teleop's banner")
            # a key pressed before then is published to nobody, and the turtle never moves
            wait_until(lambda: bool(sending_to(sim.uri, "/teleop_turtle", "/turtle1/cmd_vel")),
                       what="teleop's publisher to connect to turtlesim")
            tmux("send-keys", "Up")
            wait_until(lambda: sim.pose()["x"] > CENTRE + 1.0, what="the turtle to move forward")
            tmux("send-keys", "Left")
            wait_until(lambda: sim.pose()["theta"] > 1.0, what="the turtle to turn left")
            tmux("send-keys", "q")
            wait_until(stty.exists, what="teleop to quit")
            after = stty.read_text()
            assert " icanon" in after and " echo " in after
            assert after == (tmp_path / "before.txt").read_text()
            assert "^[[A" not in tmux("capture-pane", "-p")  # no echo while it ran
        finally:
            for pid in reversed(pids):
                try:
                    os.kill(pid, signal.SIGTERM)
                except ProcessLookupError:
                    pass
