"""The simulator window's frames: what they hold of the world, their bytes, and the picture."""

from __future__ import annotations

import os

import numpy as np
import pytest

from kame.stage.view import (
    FLOOR_GREY,
    WALL_GREY,
    Frame,
    FrameDecoder,
    FrameEncoder,
    FrameError,
    frame_of,
    scan_hits,
    wall_raster,
)
from kame.stage.world import LaserModel, Walls, World
from tests.stage.test_world import room


def facing_east(pillar: bool = False) -> World:
    world = World(Walls(room(pillar=pillar)), laser=LaserModel(beams=3, angle_min=-0.1, angle_max=0.1))
    world.spawn("r1", 1.0, 2.0, 0.0)
    return world


def test_the_raster_is_the_map_north_up() -> None:
    world = facing_east()
    raster = np.frombuffer(wall_raster(world), dtype=np.uint8).reshape(world.walls.occupied.shape)
    assert set(np.unique(raster)) == {WALL_GREY, FLOOR_GREY}
    assert (raster == WALL_GREY).sum() == world.walls.occupied.sum()
    assert np.array_equal(raster[::-1] == WALL_GREY, world.walls.occupied)  # the map's row 0 is the image's last


def test_scan_hits_lie_on_the_wall_ahead() -> None:
    world = facing_east()
    ranges = world.scans()["r1"]
    hits = np.frombuffer(scan_hits(world, "r1", ranges), dtype=np.float32).reshape(-1, 2)
    assert len(hits) == 3
    wall_x = world.walls.origin[0] + world.walls.size[0] - world.walls.resolution  # the east wall
    assert hits[:, 0] == pytest.approx(wall_x, abs=world.walls.resolution)
    assert hits[1, 1] == pytest.approx(2.0, abs=1e-3)  # the middle beam goes straight ahead
    nothing = np.full(3, np.inf)
    assert scan_hits(world, "r1", nothing) == b""


def test_frames_cross_the_pipe_with_the_raster_once() -> None:
    world = facing_east()
    raster = wall_raster(world)
    hits = {"r1": scan_hits(world, "r1", world.scans()["r1"])}
    first = frame_of(world, raster, hits)
    assert [(r.name, r.x, r.y, r.stalled) for r in first.robots] == [("r1", 1.0, 2.0, False)]
    encoder = FrameEncoder()
    one = encoder.encode(first)
    world.command("r1", 0.5, 0.0)
    for _ in range(50):
        world.step(0.01)
    second = frame_of(world, raster, {})
    two = encoder.encode(second)
    assert len(two) < len(one) - len(raster) + 1  # the raster went with the first frame only
    decoder = FrameDecoder()
    stream = one + two
    for i in range(0, len(stream), 7):  # in pieces, as a pipe delivers them
        decoder.feed(stream[i:i + 7])
    latest = decoder.latest()
    assert latest is not None and latest.raster == raster
    assert latest.robots[0].x == pytest.approx(second.robots[0].x) and latest.robots[0].x > 1.0
    assert latest.robots[0].hits == b""
    assert (latest.columns, latest.rows, latest.resolution, latest.origin) == (
        first.columns, first.rows, first.resolution, first.origin)


def test_broken_frames_are_refused() -> None:
    with pytest.raises(FrameError, match="not a simulator frame"):
        FrameDecoder().feed(b"GARBAGE" * 10)
    world = facing_east()
    without_raster = FrameEncoder()
    frame = frame_of(world, wall_raster(world), {})
    without_raster.encode(frame)
    with pytest.raises(FrameError, match="without a raster"):
        FrameDecoder().feed(without_raster.encode(frame))


def test_the_picture_has_walls_robot_and_hits() -> None:
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    pytest.importorskip("PySide6")
    from PySide6.QtGui import QColor
    from PySide6.QtWidgets import QApplication

    from kame.stage import gui

    app = QApplication.instance() or QApplication([])  # a widget application: other tests in this process need one
    assert app is not None
    world = facing_east(pillar=True)
    frame: Frame = frame_of(world, wall_raster(world), {"r1": scan_hits(world, "r1", world.scans()["r1"])})
    width, height = gui.first_size(frame)
    assert max(width, height) == gui.LARGEST_SIDE
    image = gui.render(frame, width, height)
    place = gui.world_to_window(frame, width, height)

    def colour(x: float, y: float) -> tuple[int, int, int]:
        from PySide6.QtCore import QPointF

        point = place.map(QPointF(x, y))
        pixel = QColor(image.pixel(round(point.x()), round(point.y())))
        return pixel.red(), pixel.green(), pixel.blue()

    fill = gui.ROBOT_FILL
    assert colour(1.0 - 0.08, 2.0 + 0.08) == (fill.red(), fill.green(), fill.blue())  # in the disc, off the nose
    assert colour(3.0, 3.0) == (FLOOR_GREY,) * 3
    corner = world.walls.origin
    assert colour(corner[0] + 0.02, corner[1] + 2.0) == (WALL_GREY,) * 3  # the west wall
    assert colour(0.65, 2.25) == (WALL_GREY,) * 3  # the pillar
    assert colour(0.65, 1.8) == (FLOOR_GREY,) * 3  # beside it
    hit = np.frombuffer(frame.robots[0].hits, dtype=np.float32).reshape(-1, 2)[1]
    red, green, blue = colour(float(hit[0]), float(hit[1]))
    assert red > 150 and green < 120 and blue < 120
