"""The pure turtlesim world: turtlesim 0.10.2's numbers, stepped by hand."""

from __future__ import annotations

import math
import random

import pytest

from kame.turtlesim import (
    DEFAULT_BACKGROUND,
    DEFAULT_PEN_COLOR,
    InvalidValue,
    NameTaken,
    NoSuchTurtle,
    Rgb,
    World,
    wrap_angle,
)
from kame.turtlesim.canvas import Canvas

CENTRE = 5.544444561004639  # (499 / 45) / 2 as a float32, where turtlesim spawns turtle1


def world() -> World:
    w = World(rng=random.Random(1))
    w.reset()
    return w


def run(w: World, steps: int) -> None:
    for _ in range(steps):
        w.step()


def test_turtle1_at_the_centre() -> None:
    w = world()
    assert w.names() == ["turtle1"]
    pose = w.turtle("turtle1").pose
    assert (pose.x, pose.y, pose.theta) == pytest.approx((5.544445, 5.544445, 0.0), abs=1e-6)
    assert w.width == pytest.approx(11.088889, abs=1e-6)
    assert w.canvas.pixel(10, 10) == DEFAULT_BACKGROUND == Rgb(69, 86, 255)


def test_the_tutorial_arc() -> None:
    """cmd_vel [2,0,0] [0,0,2] once: 63 steps of 16 ms until the 1 s timeout, then still."""
    w = world()
    w.command("turtle1", 2.0, 0.0, 2.0)
    report = w.step()
    assert report.updates[0].pose.linear_velocity == 2.0
    assert report.updates[0].pose.angular_velocity == 2.0
    run(w, 99)
    x = y = CENTRE
    theta = 0.0
    for _ in range(63):
        theta += 2.0 * 0.016
        x += math.cos(theta) * 2.0 * 0.016
        y += math.sin(theta) * 2.0 * 0.016
    pose = w.turtle("turtle1").pose
    assert pose.theta == pytest.approx(2.016, abs=1e-9)
    assert (pose.x, pose.y) == pytest.approx((x, y), abs=1e-9)
    assert (pose.x, pose.y) == pytest.approx((6.4240, 6.9894), abs=1e-4)
    # the continuous arc (radius v/w = 1 m around (x0, y0 + 1)) is within a few cm
    assert (pose.x, pose.y) == pytest.approx((CENTRE + math.sin(2.016), CENTRE + 1 - math.cos(2.016)), abs=0.03)
    assert pose.linear_velocity == pose.angular_velocity == 0.0


def test_holonomic_sideways_motion_and_wrap() -> None:
    w = world()
    w.teleport_absolute("turtle1", 5.0, 5.0, math.pi / 2)
    w.step()
    w.command("turtle1", 0.0, 1.0, 0.0)  # sideways = to the turtle's left = -x when facing up
    run(w, 10)
    pose = w.turtle("turtle1").pose
    assert (pose.x, pose.y) == pytest.approx((5.0 - 0.16, 5.0), abs=1e-9)
    assert wrap_angle(math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    w.command("turtle1", 0.0, 0.0, 10.0)
    run(w, 50)
    assert -math.pi <= w.turtle("turtle1").pose.theta < math.pi


def test_wall_clamp_reports_the_window_frame() -> None:
    w = world()
    w.command("turtle1", 10.0, 0.0, 0.0)
    hits = []
    for _ in range(60):
        hits.extend(w.step().hits)
    assert w.turtle("turtle1").pose.x == pytest.approx(w.width)
    assert hits and hits[0].name == "turtle1"
    assert hits[0].x > w.width and hits[0].y == pytest.approx(w.height - CENTRE)
    w.teleport_absolute("turtle1", 3.0, -2.0, 0.0)  # below the floor: y is clamped at the step
    report = w.step()
    assert w.turtle("turtle1").pose.y == 0.0
    assert report.hits[0].y == pytest.approx(w.height + 2.0)


def test_spawn_names_and_errors() -> None:
    w = world()
    assert w.spawn("", 2, 2, 0.2) == "turtle2"
    assert w.spawn("leo", 1, 1, 0) == "leo"
    with pytest.raises(NameTaken, match=r"A turtled named \[leo\] already exists"):
        w.spawn("leo", 1, 1, 0)
    w.spawn("turtle3", 1, 1, 0)
    assert w.spawn("", 1, 1, 0) == "turtle4"  # the counter skips names in use
    w.kill("turtle2")
    with pytest.raises(NoSuchTurtle, match=r"Tried to kill turtle \[turtle2\], which does not exist"):
        w.kill("turtle2")
    pose = w.turtle("leo").pose
    assert (pose.x, pose.y) == pytest.approx((1, 1))
    assert w.reset() == "turtle1"
    assert w.names() == ["turtle1"]
    assert w.spawn("", 1, 1, 0) == "turtle2"


def test_non_finite_values_are_refused() -> None:
    w = world()
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(InvalidValue):
            w.command("turtle1", bad, 0, 0)
        with pytest.raises(InvalidValue):
            w.teleport_absolute("turtle1", 1, bad, 0)
        with pytest.raises(InvalidValue):
            w.spawn("x", bad, 1, 0)
    run(w, 3)
    assert math.isfinite(w.turtle("turtle1").pose.x)


def test_pen_trail_colour_sensor_and_clear() -> None:
    w = world()
    w.command("turtle1", 2.0, 0.0, 0.0)
    report = w.step()
    assert report.updates[0].color == DEFAULT_BACKGROUND  # read before this step's line
    seg = report.segments[0]
    assert seg.color == DEFAULT_PEN_COLOR and seg.width == 3
    assert seg.start == pytest.approx((CENTRE, CENTRE)) and seg.end == pytest.approx((CENTRE + 0.032, CENTRE))
    run(w, 20)
    row = round((w.height - CENTRE) * 45)
    assert w.canvas.pixel(round(CENTRE * 45) + 20, row) == DEFAULT_PEN_COLOR
    assert w.canvas.pixel(round(CENTRE * 45) + 20, row - 3) == DEFAULT_BACKGROUND  # 3 px wide
    # the sensor sees the trail under a turtle going back over it
    w.teleport_absolute("turtle1", CENTRE + 0.3, CENTRE, 0.0)
    w.step()
    assert w.step().updates[0].color == DEFAULT_PEN_COLOR
    w.set_pen("turtle1", 255, 0, 0, 0, False)
    assert w.turtle("turtle1").pen.width == 1
    w.set_pen("turtle1", 9, 9, 9, 9, True)
    assert not w.turtle("turtle1").pen.on and w.turtle("turtle1").pen.color == Rgb(255, 0, 0)
    w.clear(Rgb(150, 86, 255))
    assert w.canvas.pixel(round(CENTRE * 45) + 20, row) == Rgb(150, 86, 255)


def test_teleports_draw_and_apply_at_the_next_step() -> None:
    w = world()
    w.teleport_relative("turtle1", 1.0, math.pi / 2)
    assert w.turtle("turtle1").pose.y == pytest.approx(CENTRE)
    report = w.step()
    pose = w.turtle("turtle1").pose
    assert (pose.x, pose.y, pose.theta) == pytest.approx((CENTRE, CENTRE + 1.0, math.pi / 2))
    assert len(report.segments) == 1 and report.changed
    w.set_pen("turtle1", 0, 0, 0, 0, True)
    w.teleport_absolute("turtle1", 1.0, 2.0, 3.0)
    assert w.step().segments == ()
    assert w.turtle("turtle1").pose.x == pytest.approx(1.0)


def test_snapshot_and_versions() -> None:
    w = world()
    v = w.snapshot().version
    w.step()
    assert w.snapshot().version == v  # nothing moved: nothing to redraw
    w.command("turtle1", 1, 0, 0)
    w.step()
    snap = w.snapshot()
    assert snap.version > v and len(snap.pixels) == 500 * 500 * 3
    assert snap.turtles[0].x == pytest.approx((CENTRE + 0.016) * 45)


def test_a_snapshot_copies_the_pixels_only_after_they_changed() -> None:
    world = World(rng=random.Random(1))
    world.reset()
    first = world.snapshot()
    world.command("turtle1", 0.0, 0.0, 1.0)  # turning in place draws nothing
    world.step()
    turned = world.snapshot()
    assert turned.version != first.version and turned.turtles != first.turtles
    assert turned.pixels is first.pixels
    world.command("turtle1", 1.0, 0.0, 0.0)
    world.step()
    moved = world.snapshot()
    assert moved.pixels is not first.pixels and moved.pixels != first.pixels
    assert moved.pixels == bytes(world.canvas.pixels)
    world.clear()
    assert world.snapshot().pixels == bytes(world.canvas.pixels) != moved.pixels


def test_canvas_lines() -> None:
    c = Canvas(20, 20, Rgb(0, 0, 0))
    c.line(2, 10, 17, 10, Rgb(1, 2, 3), 3)
    assert [c.pixel(x, 10) for x in (0, 1, 2, 18, 19)] == [Rgb(0, 0, 0), Rgb(1, 2, 3), Rgb(1, 2, 3),
                                                             Rgb(1, 2, 3), Rgb(0, 0, 0)]
    assert c.pixel(10, 9) == c.pixel(10, 11) == Rgb(1, 2, 3) and c.pixel(10, 12) == Rgb(0, 0, 0)
    c.line(5, -100, 5, 300, Rgb(9, 9, 9), 1)  # clipped, one pixel wide
    assert c.pixel(5, 0) == c.pixel(5, 19) == Rgb(9, 9, 9) and c.pixel(6, 0) == Rgb(0, 0, 0)
    c.line(0, 0, 19, 19, Rgb(7, 7, 7), 1)
    assert c.pixel(12, 12) == Rgb(7, 7, 7)


def test_the_world_knows_nothing_of_ros_and_the_gui_only_the_world() -> None:
    """ARCHITECTURE rule 4."""
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "src" / "kame" / "turtlesim"

    def imports(name: str) -> set[str]:
        found: set[str] = set()
        for node in ast.walk(ast.parse((root / name).read_text())):
            if isinstance(node, ast.Import):
                found.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom) and node.module:
                found.add(node.module)
        return found

    ros = ("rospy", "kame.node", "kame.net", "geometry_msgs", "turtlesim", "std_srvs", "PySide6")
    for pure in ("world.py", "canvas.py", "window_probe.py", "frame_codec.py"):
        assert not [m for m in imports(pure) if m.startswith(ros) and not m.startswith("kame.turtlesim")]
    # the GUI draws the world, as frames from the node (frame_codec) read by kame.fed_window's
    # window process; its start-up probe speaks window_probe's words; neither knows ROS
    assert {m for m in imports("gui.py") if m.startswith(("kame", "rospy"))} == {
        "kame.turtlesim.world", "kame.turtlesim.window_probe", "kame.turtlesim.frame_codec", "kame.fed_window"}
