"""turtle_actionlib's shape server drives turtlesim's turtle around the goal's polygon: the
controller (kame.turtle_actionlib.Polygon) fed by kame's turtlesim world, step by step as
turtlesim publishes poses, for the client's pentagon of radius 1.3; and the package's programs
and action are where the actionlib tutorial finds them."""

from __future__ import annotations

import math
import os
import random

import pytest

from kame.catkin import executables
from kame.turtle_actionlib import Polygon
from kame.turtlesim.world import World


def test_the_pentagon_is_driven_edge_by_edge_and_closes() -> None:
    world = World(rng=random.Random(1))
    world.reset()
    start = world.turtle("turtle1").pose
    shape = Polygon(edges=5, radius=1.3)
    corners = []
    for _ in range(20_000):  # 320 s of turtlesim's time at most
        if shape.finished:
            break
        pose = world.turtle("turtle1").pose
        done = shape.done_edges
        linear, angular = shape.command(pose.x, pose.y, pose.theta)
        if shape.done_edges > done:
            corners.append((pose.x, pose.y))
        world.command("turtle1", linear, 0.0, angular)
        world.step()
    assert shape.finished and len(corners) == 5
    side = 2 * 1.3 * math.sin(math.pi / 5)
    for (x0, y0), (x1, y1) in zip([(start.x, start.y), *corners], corners, strict=False):
        assert math.hypot(x1 - x0, y1 - y0) == pytest.approx(side, abs=1e-3)
    assert corners[-1] == pytest.approx((start.x, start.y), abs=1e-3)  # back where it began
    assert shape.interior_angle == pytest.approx(3 * math.pi / 5)
    assert shape.apothem == pytest.approx(1.3 * math.cos(math.pi / 5))


def test_the_package_has_the_tutorials_programs_and_action() -> None:
    package = executables.packages(os.environ)["turtle_actionlib"]
    assert all(executables.is_executable(package.path / "nodes" / name) for name in ("shape_server", "shape_client"))
    from turtle_actionlib.msg import ShapeAction, ShapeGoal, ShapeResult, Velocity

    assert ShapeGoal(edges=5, radius=1.3).edges == 5
    assert [s for s in ShapeResult.__slots__] == ["interior_angle", "apothem"]
    assert ShapeAction._type == "turtle_actionlib/ShapeAction" and Velocity._type == "turtle_actionlib/Velocity"
