"""gzclient live on a private Xvfb against a real gzserver running a red box on the ground plane:
the box drawn (a screenshot in the tour), the status bar's sim time advancing, the window's pause
stopping it and its step moving it one iteration, and the server running on once the window is
closed. Without a display gzclient says so in one line."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

from tests.gazebo_ros.gazebo_sim import gazebo
from tests.support import Proc
from tests.support.tour import shoot
from tests.turtlesim.sim import BIN, Sim, master, wait_until
from tests.turtlesim.xserver import Screenshot, find_window, xvfb

# looked for, not imported: MuJoCo loaded in this process would fix its PyOpenGL to EGL, and the
# windows other tests draw in this process (rviz's) would find no context of Qt's
if importlib.util.find_spec("mujoco") is None:
    pytest.skip("kame[gazebo] (MuJoCo) is not installed", allow_module_level=True)
pytest.importorskip("PySide6", reason="kame[gui] is not installed")
pytest.importorskip("OpenGL", reason="kame[gui] (PyOpenGL) is not installed")

WORLD = Path(__file__).resolve().parent / "data" / "red_box.world"
SIM_TIME = re.compile(r"Sim Time: (\d+) (\d+):(\d+):(\d+\.\d+)")


def red_pixels(shot: Screenshot) -> int:
    step = shot.bytes_per_pixel
    count = 0
    for y in range(0, shot.height, 4):
        row = shot.data[y * shot.bytes_per_line:y * shot.bytes_per_line + shot.width * step]
        red, green, blue = (row[2::step], row[1::step], row[0::step]) if shot.little_endian else \
            (row[step - 3::step], row[step - 2::step], row[step - 1::step])
        count += sum(1 for r, g, b in zip(red[::4], green[::4], blue[::4], strict=True)
                     if r > 150 and g < 60 and b < 60)
    return count


def sim_times(proc: Proc) -> list[tuple[str, float]]:
    """(play button, sim time) of each status line the window printed, oldest first."""
    found = []
    for line in list(proc.out):
        match = SIM_TIME.search(line)
        if line.startswith("status ") and match:
            days, hours, minutes, seconds = match.groups()
            found.append((line.split()[1], ((int(days) * 24 + int(hours)) * 60 + int(minutes)) * 60 + float(seconds)))
    return found


def send(child: Proc, line: str) -> None:
    assert child.popen.stdin is not None
    child.popen.stdin.write(line + "\n")
    child.popen.stdin.flush()


def box_position(sim: Sim) -> tuple[float, float]:
    state = yaml.safe_load(sim.run("rosservice", "call", "/gazebo/get_model_state", "red_box", "world").stdout)
    return float(state["pose"]["position"]["x"]), float(state["pose"]["position"]["y"])


@pytest.fixture(scope="module")
def live(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Sim, Proc, str]]:
    home = tmp_path_factory.mktemp("gzclient")
    with xvfb("1280x800") as display, gazebo(home, f"world_name:={WORLD}") as (sim, launch):
        yield sim, launch, display


def test_the_window_draws_the_box_follows_time_pauses_steps_and_closes_leaving_the_server(
        live: tuple[Sim, Proc, str]) -> None:
    sim, launch, display = live
    child = Proc([sys.executable, "-m", "tests.gzclient.window_child"], dict(sim.env, DISPLAY=display),
                 cwd=Path(__file__).resolve().parents[2], stdin=subprocess.PIPE)
    sim.procs.append(child)
    assert child.popen.stdin is not None
    shoot(display, "Gazebo", "gzclient_red_box", ready=lambda shot: red_pixels(shot) > 200, program=child)
    wait_until(lambda: len({t for _, t in sim_times(child)}) >= 3, timeout=30, what="sim time to advance")
    times = [t for _, t in sim_times(child)]
    assert times == sorted(times) and times[-1] > times[0]

    child.popen.stdin.write("pause\n")
    child.popen.stdin.flush()
    wait_until(lambda: any(button == "Play" for button, _ in sim_times(child)), timeout=30, what="the pause")
    paused_at = next(t for button, t in sim_times(child) if button == "Play")
    shown = len(child.out)
    wait_until(lambda: len(child.out) >= shown + 5, timeout=30, what="real time to go on")  # 1 s of stats
    assert {t for button, t in sim_times(child) if button == "Play"} == {paused_at}
    shoot(display, "Gazebo", "gzclient_paused", ready=lambda shot: red_pixels(shot) > 200)

    child.popen.stdin.write("step\n")
    child.popen.stdin.flush()
    wait_until(lambda: any(t > paused_at for _, t in sim_times(child)), timeout=30, what="the step")
    assert max(t for _, t in sim_times(child)) == pytest.approx(paused_at + 0.001, abs=1e-6)  # one max_step_size

    send(child, "drag red_box 1.5 -1")
    child.wait_line("dragged red_box selected red_box", timeout=30)
    wait_until(lambda: box_position(sim) == pytest.approx((1.5, -1.0), abs=0.05), timeout=30,
               what="the dragged box where the mouse left it")
    send(child, "insert box")  # where the view looks: where the red box was
    wait_until(lambda: "unit_box" in sim.run("rosservice", "call", "/gazebo/get_world_properties").stdout,
               timeout=30, what="the inserted box")
    wait_until(lambda: any("unit_box" in line.rsplit("drawn ", 1)[-1] for line in list(child.out)), timeout=30,
               what="the inserted box drawn while paused")
    shoot(display, "Gazebo", "gzclient_dragged_and_inserted", ready=lambda shot: red_pixels(shot) > 200)
    send(child, "delete unit_box")
    wait_until(lambda: "unit_box" not in sim.run("rosservice", "call", "/gazebo/get_world_properties").stdout,
               timeout=30, what="the deleted box gone")
    wait_until(lambda: child.out[-1].rstrip().endswith("drawn ground_plane,red_box"), timeout=30,
               what="the deleted box no longer drawn")

    child.popen.stdin.write("close\n")
    child.popen.stdin.flush()
    child.wait_line("closed", timeout=30)
    child.popen.wait(30)
    assert launch.popen.poll() is None
    assert "red_box" in sim.run("rosservice", "call", "/gazebo/get_world_properties").stdout


def test_without_a_display_gzclient_says_so_in_one_line(tmp_path: Path) -> None:
    env = dict(os.environ)
    for name in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"):
        env.pop(name, None)
    result = subprocess.run([str(BIN / "rosrun"), "gazebo_ros", "gzclient"], env=env, capture_output=True, text=True,
                            timeout=60, cwd=tmp_path)
    assert result.returncode == 0
    assert result.stderr.strip().splitlines() == [
        "gzclient: No display (DISPLAY is not set): gzclient runs headless, without a window; "
        "gzserver keeps simulating"]


def test_gazebo_runs_the_server_and_its_window_which_ends_with_it(tmp_path: Path) -> None:
    """`rosrun gazebo_ros gazebo WORLD`: the window, a process of its own, draws the server's world
    although the server's MuJoCo chose EGL for PyOpenGL in the environment the window inherits."""
    with xvfb("1280x800") as display, master(tmp_path) as sim:
        server = sim.start("gazebo_ros", "gazebo", str(WORLD), env=dict(sim.env, DISPLAY=display),
                           wait="Finished loading Gazebo ROS API Plugin.")
        shoot(display, "Gazebo", "gazebo_server_and_window", ready=lambda shot: red_pixels(shot) > 200,
              program=server)
        server.stop()
        wait_until(lambda: find_window(display, "Gazebo") is None, timeout=30, what="the window to end with gazebo")


def test_empty_world_launch_with_gui_true_opens_the_window(tmp_path: Path) -> None:
    with xvfb("1280x800") as display, master(tmp_path) as sim:
        sim.env["DISPLAY"] = display
        launch = Proc([str(BIN / "roslaunch"), "gazebo_ros", "empty_world.launch", "gui:=true",
                       f"world_name:={WORLD}"], sim.env, cwd=tmp_path)
        sim.procs.append(launch)
        shoot(display, "Gazebo", "empty_world_launch_gui", ready=lambda shot: red_pixels(shot) > 200,
              program=launch)
