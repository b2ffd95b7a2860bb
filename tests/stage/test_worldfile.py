"""Stage .world files: the floorplan bitmap, boxes and robots of the shapes ROS worlds use."""

from __future__ import annotations

import math

import numpy as np
import pytest

from kame.stage.worldfile import Box, WorldFileError, parse, rasterise

TURTLEBOT_INC = """
define kinect ranger ( sensor ( range_max 6.5 fov 58.0 samples 640 ) color "black" size [ 0.06 0.15 0.03 ] )
define turtlebot position
(
  pose [ 0.0 0.0 0.0 0.0 ]
  odom_error [0.03 0.03 999999 999999 999999 0.02]
  size [ 0.2552 0.2552 0.40 ]
  origin [ 0.0 0.0 0.0 0.0 ]
  gui_nose 1
  drive "diff"
  color "gray"
  kinect(pose [ -0.1 0.0 -0.11 0.0 ])
)
"""

MAZE_WORLD = """# a world as turtlebot_stage ships them
include "turtlebot.inc"

define floorplan model
(
  color "gray30"
  boundary 1
  gui_nose 0
  obstacle_return 1
  laser_return 1
)

resolution 0.05
interval_sim 100  # simulation timestep in milliseconds

window ( size [ 600.0 700.0 ] center [ 0.0 0.0 ] rotate [ 0.0 0.0 ] scale 60 )

floorplan ( name "maze" bitmap "maze.png" size [ 4.0 2.0 2.0 ] pose [ 2.0 1.0 0.0 0.0 ] )

define block model ( size [0.5 0.5 0.5] gui_nose 0 )
block ( pose [ 3.0 1.5 0 45 ] color "red" )

turtlebot ( pose [ 1.0 0.5 0.0 90.0 ] name "turtlebot" color "black" )
turtlebot ( pose [ 0.5 1.5 0.0 -90.0 ] name "other" )
"""


def _read(name: str) -> str:
    if name == "turtlebot.inc":
        return TURTLEBOT_INC
    raise FileNotFoundError(2, "No such file or directory")


def test_floorplan_boxes_and_robots_are_found() -> None:
    spec = parse(MAZE_WORLD, "maze.world", _read)
    assert spec.resolution == 0.05
    [plan] = spec.floorplans
    assert (plan.bitmap, plan.size, plan.pose, plan.boundary) == ("maze.png", (4.0, 2.0), (2.0, 1.0, 0.0), True)
    assert spec.boxes == [Box((0.5, 0.5), (3.0, 1.5, math.radians(45)))]
    assert [(r.name, r.pose) for r in spec.robots] == [("turtlebot", (1.0, 0.5, math.pi / 2)),
                                                      ("other", (0.5, 1.5, -math.pi / 2))]


def test_the_bitmap_is_scaled_to_the_floorplan() -> None:
    spec = parse(MAZE_WORLD, "maze.world", _read)
    image = np.full((20, 40), 255, dtype=np.uint8)  # 10 cm pixels over 4 x 2 m
    image[0:10, 0:5] = 0  # the top-left quarter metre by a metre: a wall
    grid = rasterise(spec, {"maze.png": image})
    assert (grid.width, grid.height, grid.resolution, grid.origin) == (80, 40, 0.05, (0.0, 0.0, 0.0))
    walls = grid.cells == 100
    assert walls[0, :].all() and walls[-1, :].all() and walls[:, 0].all() and walls[:, -1].all()  # boundary
    assert walls[20:39, 1:10].all() and not walls[1:20, 1:10].any()  # the image's top is +y
    # the block, a 0.5 m square turned 45 degrees about (3.0, 1.5): its corner reaches x = 3.354
    assert walls[30, 60] and walls[30, 66] and not walls[30, 68]
    assert not walls[34, 64]  # (3.225, 1.725): inside the square unturned, outside it turned


@pytest.mark.parametrize(("text", "error"), [
    ('include "missing.inc"\n', "cannot include 'missing.inc'"),
    ("floorplan ( bitmap \"m.png\" size [ 1 1 1 ] \n", "ends inside a bracket"),
    ("resolution 0.05\n", "no floorplan"),
    ('<?xml version="1.0"?>\n<sdf version="1.4"><world name="default"/></sdf>\n', "Gazebo (SDF) world"),
    ('floorplan ( bitmap "m.png" size [ 0 1 1 ] )\n', "a size above 0"),
    ('floorplan ( bitmap "m.png" size [ 1 1 1 ] pose [ 1 2 ] )\n', "pose must be"),
])
def test_bad_world_files_say_why(text: str, error: str) -> None:
    with pytest.raises(WorldFileError) as raised:
        parse(text, "bad.world", _read)
    assert error in str(raised.value)
