"""stageros's window on a real X server (Xvfb): it opens over the world and shows the robot;
-g and a missing display run the simulation without one and say so."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.support.tour import shoot
from tests.turtlesim.sim import master, wait_until

pytest.importorskip("PySide6")

PLAYGROUND = str(Path(__file__).resolve().parents[2] / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"
                 / "playground.yaml")


def test_the_window_shows_the_world_and_the_robot(tmp_path: Path) -> None:
    from kame.stage import gui, view
    from tests.turtlesim.xserver import XWindow, find_window, screenshot, xvfb

    with xvfb() as display, master(tmp_path) as live:
        env = dict(live.env, DISPLAY=display)
        env.pop("QT_QPA_PLATFORM", None)
        node = live.start("stage_ros", "stageros", PLAYGROUND, env=env, wait="Simulating [robot_0]")
        found: list[XWindow] = []

        def mapped() -> bool:
            window = find_window(display, "Stage: playground.yaml")
            found[:] = [window] if window is not None and window.viewable else []
            return bool(found)

        wait_until(lambda: mapped() or "without a window" in "".join(node.out + node.err), timeout=60,
                   what="the simulator's window to be mapped")
        assert found, "".join(node.out + node.err)
        window = found[0]
        fill = gui.ROBOT_FILL
        robot = (fill.red(), fill.green(), fill.blue())

        def robot_drawn() -> bool:
            shot = screenshot(display, window.id)
            colours = shot.colours(0, 0, shot.width, shot.height)
            return robot in colours and (view.WALL_GREY,) * 3 in colours

        wait_until(robot_drawn, timeout=30, what="the robot and the walls in the window")
        assert node.popen.poll() is None
        shoot(display, "Stage: playground.yaml", "stageros")  # the tour (tests/support/tour.py)


@pytest.mark.parametrize("display", [None, "-g"])
def test_without_a_window_the_simulation_says_why(tmp_path: Path, display: str | None) -> None:
    with master(tmp_path) as live:
        args = [PLAYGROUND] + ([display] if display else [])
        node = live.start("stage_ros", "stageros", *args, wait="Simulating [robot_0]")
        wait_until(lambda: "without a window" in "".join(node.out), what="the reason")
        said = "".join(node.out)
        assert ("-g: stageros runs without a window" in said) if display else ("No display" in said), said
