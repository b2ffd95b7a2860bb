"""The course's TurtleBot flow on kame's 2-D world: `roslaunch turtlebot_gazebo turtlebot_world.launch`,
the live /scan hits the map's walls cell by cell, `roslaunch turtlebot_teleop keyboard_teleop.launch`
in a real terminal (tmux), keys drive the robot in /odom and ground truth, `k` stops it, Ctrl-C
quits; the teleop script's key rules."""

from __future__ import annotations

import math
import os
import shutil
import signal
import subprocess
from pathlib import Path
from typing import Any

import pytest

from kame.stage.teleop import BANNER, Teleop, speeds_line
from tests.stage.sim import echo
from tests.support import REPO, Proc, sending_to
from tests.turtlesim.sim import BIN, master, wait_until


def test_keys_follow_the_scripts_rules() -> None:
    teleop = Teleop()
    teleop.press("i")
    assert (teleop.control_speed, teleop.control_turn) == (0.02, 0.0)
    for _ in range(20):
        teleop.press("i")
    assert teleop.control_speed == pytest.approx(0.2)
    teleop.press("j")
    assert teleop.control_speed == pytest.approx(0.18) and teleop.control_turn == pytest.approx(0.1)
    teleop.press("k")
    assert (teleop.control_speed, teleop.control_turn) == (0.0, 0.0)
    assert teleop.press("q") == [speeds_line(0.2 * 1.1, 1.1)]
    teleop.press(",")
    for _ in range(4):
        teleop.press("")  # quiet ticks: the direction holds for four, then stops smoothly
    assert teleop.x == -1
    teleop.press("")
    assert teleop.x == 0
    lines = [line for _ in range(14) for line in teleop.press("x")]
    assert lines[-1] == BANNER and len(lines) == 15  # the banner again every 15 speed changes


def assert_scan_hits_walls(scan: dict[str, Any]) -> None:
    """Each beam of a scan taken at the playground's origin ends in a wall cell of the world's map
    (within a cell: the beam's end lies on the wall's face) and crosses no wall before it."""
    from kame.stage import mapfile

    world = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds" / "playground.yaml"
    description = mapfile.parse_description(world.read_text())
    image = Path(description.image_path(str(world)))
    grid = mapfile.load(description, image.read_bytes(), image.name)

    def cells_near(x: float, y: float, around: int) -> Any:
        col = math.floor((x - grid.origin[0]) / grid.resolution)
        row = math.floor((y - grid.origin[1]) / grid.resolution)
        return grid.cells[max(row - around, 0):row + around + 1, max(col - around, 0):col + around + 1]

    hits = 0
    for i, distance in enumerate(scan["ranges"]):
        if not scan["range_min"] <= distance < scan["range_max"]:
            continue
        angle = scan["angle_min"] + i * scan["angle_increment"]
        end_x, end_y = distance * math.cos(angle), distance * math.sin(angle)
        assert (cells_near(end_x, end_y, 1) == 100).any(), (i, distance, "no wall where the beam ends")
        short = distance - 2 * grid.resolution  # the way there is free
        assert not (cells_near(short * math.cos(angle), short * math.sin(angle), 0) == 100).any(), (i, distance)
        hits += 1
    assert hits > len(scan["ranges"]) // 2, hits


@pytest.mark.skipif(shutil.which("tmux") is None, reason="tmux is not installed")
def test_turtlebot_world_and_keyboard_teleop(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", "simulator:=stage"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("standing in for Gazebo", timeout=30)
        world.wait_line("Simulating [robot_0]", timeout=30)
        assert sim.run("rosparam", "get", "/use_sim_time").stdout.strip() == "true"
        assert "turtlebot" in sim.run("rosparam", "get", "/robot_description").stdout
        scan = echo(sim, "/scan")  # stageros's base_scan, remapped as turtlebot_stage does
        assert len(scan["ranges"]) == 640 and scan["header"]["frame_id"] == "base_scan"
        assert_scan_hits_walls(scan)  # the robot stands at the origin, base_scan above base_link

        sock = str(tmp_path / "tmux.sock")

        def tmux(*args: str) -> str:
            return subprocess.run(["tmux", "-S", sock, *args], env=sim.env, capture_output=True, text=True,
                                  timeout=10, check=True).stdout

        tmux("new-session", "-d", "-x", "100", "-y", "40", "sh", "-c",
             f"{BIN}/roslaunch turtlebot_teleop keyboard_teleop.launch; exec sleep 60")
        pids = [int(tmux("display", "-p", "#{pid}").strip()), int(tmux("display", "-p", "#{pane_pid}").strip())]
        try:
            wait_until(lambda: "Control Your Turtlebot!" in tmux("capture-pane", "-p"), timeout=30,
                       what="teleop's banner")
            wait_until(lambda: bool(sending_to(sim.uri, "/turtlebot_teleop_keyboard", "/cmd_vel_mux/input/teleop")),
                       timeout=20, what="teleop to connect to the simulator")

            def truth_x() -> float:
                return float(echo(sim, "/base_pose_ground_truth")["pose"]["pose"]["position"]["x"])

            def holding(key: str, done: float) -> bool:  # a held key repeats
                tmux("send-keys", key * 5)
                return truth_x() > done

            wait_until(lambda: holding("i", 0.3), timeout=40, what="the robot to drive forward")
            assert float(echo(sim, "/odom")["pose"]["pose"]["position"]["x"]) > 0.2
            tmux("send-keys", "k")
            wait_until(lambda: echo(sim, "/odom")["twist"]["twist"]["linear"]["x"] == 0.0, timeout=20,
                       what="k to stop the robot")
            tmux("send-keys", "C-c")
            wait_until(lambda: "sleep" in tmux("display", "-p", "#{pane_current_command}"), timeout=20,
                       what="Ctrl-C to end keyboard_teleop.launch")
        finally:
            for pid in reversed(pids):
                try:
                    os.kill(pid, signal.SIGTERM)
                except ProcessLookupError:
                    pass
