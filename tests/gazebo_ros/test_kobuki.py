"""The Kobuki's plugin's pure pieces: which bumper a contact presses, a cliff event's bottom, and
kobuki_msgs as kame ships it (the three messages the plugin uses, md5sums as upstream's)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import pytest

from kobuki_msgs.msg import BumperEvent, CliffEvent, MotorPower

# pure, but its package imports the World's modules: skipped without kame[gazebo], as its neighbours
pytest.importorskip("kame.gazebo.engine", reason="kame[gazebo] (MuJoCo) is not installed")

from kame.gazebo_ros.plugins.kobuki import bumpers_pressed, cliff_bottom


@dataclass
class Touch:
    position: tuple[float, float, float]
    normal: tuple[float, float, float]


def towards(angle: float, height: float = 0.05) -> Touch:
    return Touch((0.0, 0.0, height), (math.cos(angle), math.sin(angle), 0.0))


def test_a_contacts_direction_from_the_heading_picks_the_bumper() -> None:
    heading = 3.0  # facing nearly -x: angles are taken from the heading, across the +-pi seam
    left, centre, right = BumperEvent.LEFT, BumperEvent.CENTER, BumperEvent.RIGHT
    assert bumpers_pressed([towards(heading)], heading, 0.0) == {centre}
    assert bumpers_pressed([towards(heading + 0.6)], heading, 0.0) == {left}  # 34 degrees to the left
    assert bumpers_pressed([towards(heading - 1.2)], heading, 0.0) == {right}
    assert bumpers_pressed([towards(heading + 2.0)], heading, 0.0) == set()  # behind: the Kobuki has no rear bumper
    both = [towards(heading + 0.3), towards(heading - 0.3)]
    assert bumpers_pressed(both, heading, 0.0) == {centre}
    assert bumpers_pressed([towards(heading, height=0.005)], heading, 0.0) == set()  # the casters on the floor
    assert bumpers_pressed([towards(heading, height=0.55)], heading, 0.5) == {centre}  # above the base's height


def test_a_cliff_events_bottom_is_millimetres_to_the_floor() -> None:
    assert cliff_bottom(0.0315, 0.15) == 32
    assert cliff_bottom(math.inf, 0.15) == 150  # nothing within range: the range's end
    assert cliff_bottom(math.inf, 1e6) == 65535  # a uint16


def test_kobuki_msgs_md5sums_are_upstreams() -> None:
    # as code generated from kobuki_msgs quotes them (gennodejs, roslisp, rosjava)
    assert BumperEvent._md5sum == "ffe360cd50f14f9251d9844083e72ac5"
    assert CliffEvent._md5sum == "c5b106efbb1427a94f517c5e05f06295"
    assert MotorPower._md5sum == "8f77c0161e0f2021493136bb5f3f0e51"
    assert (CliffEvent.LEFT, CliffEvent.CENTER, CliffEvent.RIGHT, CliffEvent.FLOOR, CliffEvent.CLIFF) == (0, 1, 2, 0, 1)
    assert (BumperEvent.RELEASED, BumperEvent.PRESSED, MotorPower.OFF, MotorPower.ON) == (0, 1, 0, 1)
