"""Debian's real rviz 1.14 (the reference peer) and kame's rviz show kame's TurtleBot world alike:
on a private Xvfb, against kame's master running `turtlebot_world.launch gui:=false`, map_server
on the same world and map -> odom from tf2_ros's static_transform_publisher, each draws (read back
from the screen) the map's walls and free cells where the map file has them, the scan's points on
the walls and the robot at its pose; its Displays panel first flags the Map and the scan (no map,
no map -> odom yet: their names in rviz's warning and error colours), then flags nothing; and
Debian's rviz logs no error to /rosout.

The config (tests/data/rviz/turtlebot_world_top_down.rviz) is a top-down orthographic view of the
map frame at 50 pixels a metre, with the scan in a green no other display uses; the robot model has
no material, which rviz draws in its default red. kame's rviz with the course's own configs:
tests/rviz/test_turtlebot_launchers.py."""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.support import REPO, Proc, have_debian_ros
from tests.turtlesim.sim import BIN, master

np = pytest.importorskip("numpy", reason="the 2-D world needs kame[sim]")

DEBIAN_RVIZ = "/usr/bin/rviz"
CONFIG = REPO / "tests" / "data" / "rviz" / "turtlebot_world_top_down.rviz"
WORLD = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds" / "playground.yaml"
SCALE = 50.0  # pixels a metre, the config's TopDownOrtho Scale
BACKGROUND = (48, 48, 48)  # the config's Background Color
# Mesa's GLSL linker under Xvfb complains of rviz's own map shader (indexed_8bit_image) and rviz
# logs it as an error; the map is drawn all the same (checked pixel by pixel below)
MESA_SHADER_COMPLAINT = "GLSL link result"


@dataclass(frozen=True)
class Area:
    x: int
    y: int
    width: int
    height: int


def pixels(shot: Any) -> Any:
    """A screenshot as an (height, width, 3) array of red, green, blue."""
    raw = np.frombuffer(shot.data[:shot.height * shot.bytes_per_line], dtype=np.uint8)
    rows = raw.reshape(shot.height, shot.bytes_per_line)[:, :shot.width * shot.bytes_per_pixel]
    pixel = rows.reshape(shot.height, shot.width, shot.bytes_per_pixel)
    if shot.little_endian:  # B, G, R(, pad)
        return pixel[:, :, 2::-1][:, :, :3].astype(np.int32)
    return pixel[:, :, -3:].astype(np.int32)


def render_area(image: Any) -> Area | None:
    """Where the 3-D view is: the columns and rows that show the background for over 100 pixels
    (the map leaves a margin of it on every side; the Displays panel's colour swatch is smaller)."""
    background = (image == BACKGROUND).all(axis=2)
    columns = np.flatnonzero(background.sum(axis=0) > 100)
    rows = np.flatnonzero(background.sum(axis=1) > 100)
    if not len(columns) or not len(rows):
        return None
    return Area(int(columns[0]), int(rows[0]), int(columns[-1] + 1 - columns[0]), int(rows[-1] + 1 - rows[0]))


def green(image: Any) -> Any:
    return (image[:, :, 1] > 180) & (image[:, :, 0] < 100) & (image[:, :, 2] < 100)


def red(image: Any) -> Any:
    return (image[:, :, 0] > 120) & (image[:, :, 1] < 60) & (image[:, :, 2] < 60)


def status_coloured(image: Any) -> Any:
    """The orange (warning) and red (error) rviz writes a flagged display's name in."""
    r, g, b = image[:, :, 0], image[:, :, 1], image[:, :, 2]
    return (r > 150) & (r - b > 90) & (g < 170)


def viewer_command(viewer: str) -> list[str]:
    if viewer == "debian":
        if not have_debian_ros():
            pytest.skip("Debian's ROS 1 is not installed")
        if not os.path.exists(DEBIAN_RVIZ):
            pytest.skip("Debian's rviz is not installed (apt-get install rviz; scripts/install-ros-peers.sh)")
        return [DEBIAN_RVIZ, "-d", str(CONFIG)]
    pytest.importorskip("OpenGL", reason="kame's rviz draws through PyOpenGL (pip install 'kame[gui]')")
    pytest.importorskip("PySide6")
    return [str(BIN / "rosrun"), "rviz", "rviz", "-d", str(CONFIG)]


@pytest.mark.parametrize("viewer", ["debian", "kame"])
def test_rviz_shows_the_robot_scan_and_map(tmp_path: Path, viewer: str) -> None:
    command = viewer_command(viewer)
    from kame.stage import mapfile
    from tests.turtlesim.xserver import find_shown_window, screenshot, xvfb

    description = mapfile.parse_description(WORLD.read_text())
    image_file = Path(description.image_path(str(WORLD)))
    grid = mapfile.load(description, image_file.read_bytes(), image_file.name)

    with master(tmp_path) as sim, xvfb("1024x768") as display:
        rosout = Proc([str(BIN / "rostopic"), "echo", "/rosout"], sim.env, cwd=sim.home)
        sim.procs.append(rosout)
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", "gui:=false",
                      "simulator:=stage"], sim.env,
                     cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=60)
        # Debian's rviz runs under the system's ROS with this environment: kame's master, the display
        rviz = Proc(command, dict(sim.env, DISPLAY=display, LIBGL_ALWAYS_SOFTWARE="1"), cwd=sim.home)
        sim.procs.append(rviz)

        def wait_for(what: str, predicate: Callable[[], Any], timeout: float) -> Any:
            deadline = time.monotonic() + timeout
            while time.monotonic() < deadline:
                found = predicate()
                if found is not None and found is not False:
                    return found
                assert rviz.popen.poll() is None, f"rviz exited:\n{''.join(rviz.out)}\n{''.join(rviz.err)}"
                time.sleep(0.5)
            raise AssertionError(f"timed out waiting for {what}:\n{''.join(rviz.out)}\n{''.join(rviz.err)}")

        window = wait_for("rviz's window", lambda: find_shown_window(display, f"{CONFIG.name} - RViz"), timeout=120)

        def shown() -> Any:
            return pixels(screenshot(display, window.id))

        area = wait_for("rviz's 3-D view", lambda: render_area(shown()), timeout=60)

        def flagged(image: Any) -> bool:  # in the Displays tree's name column
            return bool(status_coloured(image[area.y:area.y + area.height, 40:max(area.x - 160, 140)]).any())

        wait_for("rviz to flag the displays that lack the map and map -> odom", lambda: flagged(shown()), timeout=60)

        sim.procs.append(Proc([str(BIN / "rosrun"), "map_server", "map_server", str(WORLD)], sim.env, cwd=sim.home))
        sim.procs.append(Proc([str(BIN / "rosrun"), "tf2_ros", "static_transform_publisher",
                               "0", "0", "0", "0", "0", "0", "map", "odom"], sim.env, cwd=sim.home))

        def drawn() -> Any:
            """The view once nothing is flagged and the scan, the robot and the map's free space show
            (a screenshot between the map display's status turning OK and its first frame drawn showed
            the background where the walls are, beside a second suite)."""
            image = shown()
            view = image[area.y:area.y + area.height, area.x:area.x + area.width]
            if flagged(image) or green(view).sum() < 50 or red(view).sum() < 50:
                return None
            if (view.min(axis=2) > 215).sum() < 100_000:  # the free cells, white: the map is not drawn yet
                return None
            return view

        view = wait_for("rviz to draw the map, the scan and the robot", drawn, timeout=90)

    # each pixel's centre in the map frame, and the map cell under it
    ys, xs = np.mgrid[0:area.height, 0:area.width]
    world_x = (xs + 0.5 - area.width / 2) / SCALE
    world_y = (area.height / 2 - ys - 0.5) / SCALE
    cols = np.floor((world_x - grid.origin[0]) / grid.resolution).astype(int)
    rows = np.floor((world_y - grid.origin[1]) / grid.resolution).astype(int)
    inside = (cols >= 1) & (cols < grid.width - 1) & (rows >= 1) & (rows < grid.height - 1)

    def around(cells: int, value: int) -> Any:
        """Per pixel: is any map cell within `cells` of the one under it `value`?"""
        padded = np.pad(grid.cells == value, cells)
        near = np.zeros(grid.cells.shape, dtype=bool)
        for dr in range(2 * cells + 1):
            for dc in range(2 * cells + 1):
                near |= padded[dr:dr + grid.height, dc:dc + grid.width]
        return np.where(inside, near[rows.clip(0, grid.height - 1), cols.clip(0, grid.width - 1)], False)

    # the robot: a red disc of the TurtleBot's radius (0.177 m) at the origin, where the world starts it
    robot = red(view)
    assert abs(world_x[robot].mean()) < 0.06 and abs(world_y[robot].mean()) < 0.06, (world_x[robot].mean(),
                                                                                      world_y[robot].mean())
    disc = math.pi * (0.177 * SCALE) ** 2
    assert 0.6 * disc < robot.sum() < 1.6 * disc, (robot.sum(), disc)
    # the scan: its green points lie on the map's walls
    scan = green(view)
    off_walls = scan & ~around(3, 100)
    assert off_walls.sum() <= scan.sum() // 50, (off_walls.sum(), scan.sum())
    # the map: black over walls and white over free cells, away from the edges between them
    drawn_over = scan | robot  # and their anti-aliased edges, a few pixels wide
    for _ in range(3):
        drawn_over = drawn_over | np.roll(drawn_over, 1, 0) | np.roll(drawn_over, -1, 0)
        drawn_over = drawn_over | np.roll(drawn_over, 1, 1) | np.roll(drawn_over, -1, 1)
    plain = ~drawn_over
    walls = plain & around(1, 100) & ~around(1, 0) & ~around(1, -1)
    free = plain & around(1, 0) & ~around(1, 100) & ~around(1, -1)
    assert walls.sum() > 5000 and free.sum() > 100_000, (walls.sum(), free.sum())
    assert (view[walls].max(axis=1) < 40).all(), view[walls][view[walls].max(axis=1) >= 40][:5]
    assert (view[free].min(axis=1) > 215).all(), view[free][view[free].min(axis=1) <= 215][:5]
    # outside the map: the background
    assert (view[~inside & ~around(0, 100)] == BACKGROUND).all(axis=1).mean() > 0.95

    if viewer == "debian":
        logged = [entry for document in "".join(rosout.out).split("\n---\n") if document.strip()
                  for entry in [yaml.safe_load(document)] if str(entry.get("name", "")).startswith("/rviz")]
        assert logged, "".join(rosout.out)  # rviz's log reaches /rosout, so its errors would be seen
        errors = [entry["msg"] for entry in logged
                  if int(entry["level"]) >= 8 and MESA_SHADER_COMPLAINT not in str(entry["msg"])]
        assert errors == [], errors
