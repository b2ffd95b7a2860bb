"""What the simulator's window shows, and its bytes: the walls, each robot and its laser's hits.

Rules: pure (a World in, frames and bytes out). A frame is a fixed header, the robots (pose,
radius, bumper, name, the points where its last scan hit something), and the walls' raster
only when it differs from the last one the encoder sent: walls never change while a world
runs, so the raster crosses the pipe once. The raster is grey, one byte a cell, row 0 at the
top (north), as an image of the map. The window process may be slow: its feeder drops frames,
never the raster, because the encoder decides at sending time.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from kame.protocol.latest_frame import LatestFrameDecoder
from kame.stage.world import World

WALL_GREY, FLOOR_GREY = 40, 235

_MAGIC = b"KSF1"
# magic, columns, rows, resolution, origin x, y, robots, raster bytes (0: unchanged)
_HEADER = struct.Struct("<4sIIdddII")
# x, y, theta, radius, stalled, name length, hit count; then the name and the hits (float32 x, y)
_ROBOT = struct.Struct("<ddddBHI")


class FrameError(ValueError):
    """Bytes that are not a frame of this codec."""


@dataclass(frozen=True)
class RobotView:
    name: str
    x: float
    y: float
    theta: float
    radius: float
    stalled: bool
    hits: bytes  # float32 (x, y) pairs in the world frame, where the last scan's beams ended on something


@dataclass(frozen=True)
class Frame:
    columns: int
    rows: int
    resolution: float
    origin: tuple[float, float]  # the world position of the map's lower-left corner
    raster: bytes  # grey, columns x rows, row 0 at the top
    robots: tuple[RobotView, ...]


def wall_raster(world: World) -> bytes:
    """The walls as a grey image: dark walls on a light floor, north up."""
    occupied = world.walls.occupied[::-1]
    return np.where(occupied, WALL_GREY, FLOOR_GREY).astype(np.uint8).tobytes()


def scan_hits(world: World, name: str, ranges: np.ndarray) -> bytes:
    """Where a robot's beams with a finite range ended, in the world frame, as float32 pairs."""
    laser = world.laser
    pose = world.robot(name).pose
    seen = np.isfinite(ranges)
    angles = pose.theta + laser.angles()[seen]
    cos_t, sin_t = math.cos(pose.theta), math.sin(pose.theta)
    origin_x = pose.x + cos_t * laser.mount_x - sin_t * laser.mount_y
    origin_y = pose.y + sin_t * laser.mount_x + cos_t * laser.mount_y
    reach = ranges[seen]
    points = np.empty((reach.size, 2), dtype=np.float32)
    points[:, 0] = origin_x + reach * np.cos(angles)
    points[:, 1] = origin_y + reach * np.sin(angles)
    return points.tobytes()


def frame_of(world: World, raster: bytes, hits: Mapping[str, bytes]) -> Frame:
    """The world as the window draws it now; `hits` holds each robot's newest scan_hits."""
    rows, columns = world.walls.occupied.shape
    robots = tuple(RobotView(state.name, state.pose.x, state.pose.y, state.pose.theta, world.robot_model.radius,
                             state.stalled, hits.get(state.name, b""))
                   for state in (world.robot(name) for name in world.names()))
    return Frame(columns, rows, world.walls.resolution, world.walls.origin, raster, robots)


class FrameEncoder:
    def __init__(self) -> None:
        self._sent: bytes | None = None

    def encode(self, frame: Frame) -> bytes:
        raster = b"" if frame.raster is self._sent else frame.raster
        self._sent = frame.raster
        parts = [_HEADER.pack(_MAGIC, frame.columns, frame.rows, frame.resolution, frame.origin[0],
                              frame.origin[1], len(frame.robots), len(raster))]
        for robot in frame.robots:
            name = robot.name.encode()
            parts += [_ROBOT.pack(robot.x, robot.y, robot.theta, robot.radius, robot.stalled, len(name),
                                  len(robot.hits) // 8), name, robot.hits]
        parts.append(raster)
        return b"".join(parts)


class FrameDecoder(LatestFrameDecoder[Frame]):
    """Feed it bytes as they arrive; `latest()` is the newest whole frame (None before the first)."""

    error = FrameError

    def _parse(self, buffer: bytearray) -> tuple[Frame, int] | None:
        if len(buffer) < _HEADER.size:
            return None
        magic, columns, rows, resolution, origin_x, origin_y, count, raster_size = _HEADER.unpack_from(buffer)
        if magic != _MAGIC:
            raise FrameError(f"not a simulator frame (starts {bytes(buffer[:4])!r})")
        offset = _HEADER.size
        robots = []
        for _ in range(count):
            if len(buffer) < offset + _ROBOT.size:
                return None
            x, y, theta, radius, stalled, name_size, hit_count = _ROBOT.unpack_from(buffer, offset)
            offset += _ROBOT.size
            end = offset + name_size + hit_count * 8
            if len(buffer) < end:
                return None
            name = bytes(buffer[offset:offset + name_size]).decode()
            robots.append(RobotView(name, x, y, theta, radius, bool(stalled), bytes(buffer[offset + name_size:end])))
            offset = end
        if len(buffer) < offset + raster_size:
            return None
        raster = self._raster_at(buffer, offset, raster_size, columns * rows, f"a {columns}x{rows} map")
        return Frame(columns, rows, resolution, (origin_x, origin_y), raster, tuple(robots)), offset + raster_size
