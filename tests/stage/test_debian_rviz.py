"""Debian's real rviz 1.14 (the reference peer) shows kame's TurtleBot world: on a private Xvfb,
against kame's master running `turtlebot_world.launch gui:=false`, map_server on the same world and
map -> odom from tf2_ros's static_transform_publisher, rviz draws (read back from the screen) the
map's walls and free cells where the map file has them, the scan's points on the walls, and the
robot at its pose; its Displays panel shows no warning or error, and it logs no error to /rosout.

The config (tests/data/rviz/turtlebot_world_top_down.rviz) is a top-down orthographic view of the
map frame at 50 pixels a metre, with the scan in a green no other display uses; the robot model has
no material, which rviz draws in its default red. kame's own rviz on the same world:
tests/rviz/test_turtlebot_launchers.py."""

from __future__ import annotations

import math
import os
import re
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.support import REPO, Proc, have_debian_ros
from tests.turtlesim.sim import BIN, master

RVIZ = "/usr/bin/rviz"
CONFIG = REPO / "tests" / "data" / "rviz" / "turtlebot_world_top_down.rviz"
WORLD = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds" / "playground.yaml"
SCALE = 50.0  # pixels a metre, the config's TopDownOrtho Scale
# Mesa's GLSL linker under Xvfb complains of rviz's own map shader (indexed_8bit_image) and rviz
# logs it as an error; the map is drawn all the same (checked pixel by pixel below)
MESA_SHADER_COMPLAINT = "GLSL link result"

pytestmark = [
    pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed"),
    pytest.mark.skipif(not os.path.exists(RVIZ),
                       reason="Debian's rviz is not installed (apt-get install rviz; scripts/install-ros-peers.sh)"),
]


@dataclass(frozen=True)
class Area:
    x: int
    y: int
    width: int
    height: int


def render_area(display: str, window_id: str) -> Area | None:
    """Where rviz's Ogre render window sits in its main window: the largest nameless descendant."""
    tree = subprocess.run(["xwininfo", "-tree", "-id", window_id], env=dict(os.environ, DISPLAY=display),
                          capture_output=True, text=True, timeout=10).stdout
    found = [Area(int(x), int(y), int(w), int(h)) for w, h, x, y in
             re.findall(r"\(has no name\): \(\)\s+(\d+)x(\d+)\+-?\d+\+-?\d+\s+\+(-?\d+)\+(-?\d+)", tree)]
    return max(found, key=lambda a: a.width * a.height, default=None)


def is_green(rgb: tuple[int, int, int]) -> bool:
    return rgb[1] > 180 and rgb[0] < 100 and rgb[2] < 100


def is_red(rgb: tuple[int, int, int]) -> bool:
    return rgb[0] > 120 and rgb[1] < 60 and rgb[2] < 60


def is_status_colour(rgb: tuple[int, int, int]) -> bool:
    """The orange (warning) or red (error) rviz writes a display's name in; Ok names are blue."""
    r, g, b = rgb
    return r > 150 and r - b > 90 and g < 170


def test_debian_rviz_shows_the_robot_scan_and_map(tmp_path: Path) -> None:
    pytest.importorskip("numpy", reason="the 2-D world needs kame[sim]")
    from kame.stage import mapfile
    from tests.turtlesim.xserver import find_window, screenshot, xvfb

    description = mapfile.parse_description(WORLD.read_text())
    image = Path(description.image_path(str(WORLD)))
    grid = mapfile.load(description, image.read_bytes(), image.name)

    def cell(x: float, y: float) -> tuple[int, int]:
        return (math.floor((x - grid.origin[0]) / grid.resolution), math.floor((y - grid.origin[1]) / grid.resolution))

    def uniform_around(x: float, y: float) -> int | None:
        """The cells' value around (x, y) when its 3 x 3 cells agree (off the walls' pixel-rounded edges)."""
        col, row = cell(x, y)
        if not (1 <= col < grid.width - 1 and 1 <= row < grid.height - 1):
            return None
        values = {int(v) for v in grid.cells[row - 1:row + 2, col - 1:col + 2].flat}
        return values.pop() if len(values) == 1 else None

    def near_wall(x: float, y: float, cells: int = 3) -> bool:
        col, row = cell(x, y)
        return bool((grid.cells[max(row - cells, 0):row + cells + 1, max(col - cells, 0):col + cells + 1] == 100).any())

    with master(tmp_path) as sim, xvfb("1024x768") as display:
        rosout = Proc([str(BIN / "rostopic"), "echo", "/rosout"], sim.env, cwd=sim.home)
        sim.procs.append(rosout)
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", "gui:=false"], sim.env,
                     cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=60)
        # Debian's rviz under the system's ROS: its own environment, kame's master, the private display
        rviz_env = dict(sim.env, DISPLAY=display, LIBGL_ALWAYS_SOFTWARE="1")
        rviz = Proc([RVIZ, "-d", str(CONFIG)], rviz_env, cwd=sim.home)
        sim.procs.append(rviz)

        def wait_for(what: str, predicate: Callable[[], Any], timeout: float) -> Any:
            deadline = time.monotonic() + timeout
            while time.monotonic() < deadline:
                found = predicate()
                if found:
                    return found
                assert rviz.popen.poll() is None, f"rviz exited:\n{''.join(rviz.out)}\n{''.join(rviz.err)}"
                time.sleep(0.5)
            raise AssertionError(f"timed out waiting for {what}:\n{''.join(rviz.out)}\n{''.join(rviz.err)}")

        title = f"{CONFIG.name} - RViz"
        window = wait_for("rviz's window", lambda: find_window(display, title), timeout=120)
        area = wait_for("rviz's render window", lambda: render_area(display, window.id), timeout=60)
        names = Area(40, area.y, max(area.x - 200, 100), area.height)  # the Displays tree's name column

        def statuses_shown() -> bool:
            shot = screenshot(display, window.id)
            return any(is_status_colour(rgb) for rgb in shot.colours(names.x, names.y, names.x + names.width,
                                                                      names.y + names.height))

        # no map yet and no map -> odom: the Map and the scan are flagged (which the check below must not see)
        wait_for("rviz to flag the displays that lack the map and map -> odom", statuses_shown, timeout=60)

        sim.procs.append(Proc([str(BIN / "rosrun"), "map_server", "map_server", str(WORLD)], sim.env, cwd=sim.home))
        sim.procs.append(Proc([str(BIN / "rosrun"), "tf2_ros", "static_transform_publisher",
                               "0", "0", "0", "0", "0", "0", "map", "odom"], sim.env, cwd=sim.home))
        centre_x, centre_y = area.x + area.width / 2, area.y + area.height / 2

        def world_point(px: int, py: int) -> tuple[float, float]:
            return (px + 0.5 - centre_x) / SCALE, (centre_y - py - 0.5) / SCALE

        def drawn() -> Any:
            """The screenshot once rviz shows no flagged display and draws the scan and the robot."""
            if statuses_shown():
                return None
            shot = screenshot(display, window.id)
            pixels = [(px, py) for px in range(area.x, area.x + area.width)
                      for py in range(area.y, area.y + area.height)]
            green = [p for p in pixels if is_green(shot.rgb(*p))]
            red = [p for p in pixels if is_red(shot.rgb(*p))]
            return (shot, green, red) if len(green) > 50 and len(red) > 50 else None

        shot, green, red = wait_for("rviz to draw the map, the scan and the robot", drawn, timeout=90)

        # the robot: a disc of the TurtleBot's radius (0.177 m) at the origin, where the world starts it
        mean_x = sum(world_point(*p)[0] for p in red) / len(red)
        mean_y = sum(world_point(*p)[1] for p in red) / len(red)
        assert abs(mean_x) < 0.06 and abs(mean_y) < 0.06, (mean_x, mean_y)
        disc = math.pi * (0.177 * SCALE) ** 2
        assert 0.6 * disc < len(red) < 1.6 * disc, (len(red), disc)
        # the scan: every green point lies on a wall of the map
        off_walls = [p for p in green if not near_wall(*world_point(*p))]
        assert len(off_walls) <= len(green) // 50, (len(off_walls), len(green), off_walls[:10])
        # the map: walls black and free cells white, sampled every 5 pixels away from walls' edges
        checked = 0
        for px in range(area.x + 2, area.x + area.width, 5):
            for py in range(area.y + 2, area.y + area.height, 5):
                rgb = shot.rgb(px, py)
                expected = uniform_around(*world_point(px, py))
                if expected is None or is_green(rgb) or is_red(rgb):
                    continue
                checked += 1
                if expected == 100:
                    assert max(rgb) < 40, (px, py, rgb, "a wall")
                elif expected == 0:
                    assert min(rgb) > 215, (px, py, rgb, "free")
        assert checked > 0.8 * (grid.width * grid.resolution * SCALE / 5) ** 2, checked

    logged = [entry for document in "".join(rosout.out).split("\n---\n") if document.strip()
              for entry in [yaml.safe_load(document)] if str(entry.get("name", "")).startswith("/rviz")]
    assert logged, "".join(rosout.out)  # rviz's log reaches /rosout, so its errors would be seen
    errors = [entry["msg"] for entry in logged
              if int(entry["level"]) >= 8 and MESA_SHADER_COMPLAINT not in str(entry["msg"])]
    assert errors == [], errors
