"""The turtlesim world: turtles, their pens and the trails they leave, stepped by its owner.

Rules: knows nothing of ROS or of any GUI and never reads a clock. Its owner calls `step(dt)`
(turtlesim steps every 16 ms with dt = 0.016 s) and publishes what the step reports; the
command timeout counts the world's own time, so a run is deterministic.

The numbers and the order of one step are those of ros_tutorials' turtlesim 0.10.2
(turtle.cpp): queued teleports first (each draws a line when the pen is down), then the 1 s
command timeout, then the motion
    theta = wrap(theta + w dt);  x += (cos th vx - sin th vy) dt;  y += (sin th vx + cos th vy) dt
then the wall clamp (reported with the unclamped position in the window's top-down frame), the
pose and the colour under the turtle, and last the line from the old to the new position.
Internally positions are kept as turtle.cpp keeps them: metres in the window frame (y down).
"""

from __future__ import annotations

import math
import random
import struct
from dataclasses import dataclass, field

from kame.turtlesim.canvas import Canvas, Rgb

WINDOW_PIXELS = 500
PIXELS_PER_METRE = 45.0  # a turtle image is 45 px, and that is one metre
UPDATE_PERIOD = 0.016  # seconds: the Qt timer interval, also the fixed dt of a step
COMMAND_TIMEOUT = 1.0  # seconds without cmd_vel before the velocities drop to zero
DEFAULT_BACKGROUND = Rgb(69, 86, 255)
DEFAULT_PEN_COLOR = Rgb(179, 184, 255)
DEFAULT_PEN_WIDTH = 3
IMAGE_COUNT = 8  # turtlesim's images/ (the window's); each spawned turtle gets one at random


class TurtleError(Exception):
    """A request the world refuses; the text is what turtlesim logs."""


class NameTaken(TurtleError):
    pass


class NoSuchTurtle(TurtleError):
    pass


class InvalidValue(TurtleError):
    pass


def wrap_angle(angle: float) -> float:
    """Into [-pi, pi), as turtlesim's normalizeAngle."""
    return angle - 2.0 * math.pi * math.floor((angle + math.pi) / (2.0 * math.pi))


@dataclass(frozen=True)
class Pen:
    color: Rgb = DEFAULT_PEN_COLOR
    width: int = DEFAULT_PEN_WIDTH
    on: bool = True


@dataclass(frozen=True)
class Pose:
    """A turtle's pose in the world frame (origin bottom left, y up), as turtlesim/Pose."""
    x: float
    y: float
    theta: float
    linear_velocity: float = 0.0
    angular_velocity: float = 0.0


@dataclass(frozen=True)
class TurtleView:
    name: str
    pose: Pose
    pen: Pen
    image: int


@dataclass(frozen=True)
class Segment:
    """A line a pen drew, in world metres (y up)."""
    start: tuple[float, float]
    end: tuple[float, float]
    color: Rgb
    width: int


@dataclass(frozen=True)
class TurtleUpdate:
    """What a step publishes for one turtle: its pose and the colour under it."""
    name: str
    pose: Pose
    color: Rgb


@dataclass(frozen=True)
class WallHit:
    """A turtle pushed past a wall; x and y are the unclamped position in the window frame
    (metres, y down), which is what turtlesim prints."""
    name: str
    x: float
    y: float


@dataclass(frozen=True)
class StepReport:
    updates: tuple[TurtleUpdate, ...]
    hits: tuple[WallHit, ...]
    segments: tuple[Segment, ...]
    changed: bool


@dataclass(frozen=True)
class Sprite:
    """A turtle as a GUI draws it: pixel position (window frame) and heading."""
    name: str
    x: float
    y: float
    theta: float
    image: int


@dataclass(frozen=True)
class Snapshot:
    """Everything a GUI needs to draw one frame."""
    width: int
    height: int
    pixels: bytes  # RGB888, rows top to bottom: background and trails
    turtles: tuple[Sprite, ...]
    version: int


@dataclass
class _Teleport:
    relative: bool
    x: float = 0.0
    y: float = 0.0
    theta: float = 0.0
    linear: float = 0.0


@dataclass
class _Turtle:
    name: str
    x: float  # metres, window frame (y down)
    y: float
    theta: float
    image: int
    pen: Pen = field(default_factory=Pen)
    vx: float = 0.0
    vy: float = 0.0
    w: float = 0.0
    last_command: float = -math.inf
    teleports: list[_Teleport] = field(default_factory=list)


class World:
    """The simulation of one turtlesim window."""

    def __init__(self, width: int = WINDOW_PIXELS, height: int = WINDOW_PIXELS,
                 background: Rgb = DEFAULT_BACKGROUND, rng: random.Random | None = None) -> None:
        self.width_px = width
        self.height_px = height
        self.width = (width - 1) / PIXELS_PER_METRE  # metres: 11.088889 for 500 px
        self.height = (height - 1) / PIXELS_PER_METRE
        self.background = background
        self.canvas = Canvas(width, height, background)
        self._pixels = (-1, b"")  # (canvas revision, its pixels): one copy per change, not per frame
        self.time = 0.0
        self.version = 0
        self._rng = rng or random.Random()
        self._turtles: dict[str, _Turtle] = {}
        self._counter = 0

    # ---------------------------------------------------------------- queries

    @property
    def centre(self) -> tuple[float, float]:
        return self.width / 2.0, self.height / 2.0

    def names(self) -> list[str]:
        return sorted(self._turtles)

    def has(self, name: str) -> bool:
        return name in self._turtles

    def turtle(self, name: str) -> TurtleView:
        t = self._get(name)
        return TurtleView(t.name, self._pose(t), t.pen, t.image)

    def snapshot(self) -> Snapshot:
        sprites = tuple(Sprite(t.name, t.x * PIXELS_PER_METRE, t.y * PIXELS_PER_METRE, t.theta, t.image)
                        for t in self._sorted())
        if self._pixels[0] != self.canvas.revision:
            self._pixels = (self.canvas.revision, bytes(self.canvas.pixels))
        return Snapshot(self.width_px, self.height_px, self._pixels[1], sprites, self.version)

    # ---------------------------------------------------------------- requests

    def spawn(self, name: str, x: float, y: float, theta: float) -> str:
        """A new turtle (positions are not validated, as in turtlesim); an empty name becomes
        turtle<N> from a counter, skipping names in use. Returns the name."""
        _finite(x, y, theta)
        if not name:
            while True:
                self._counter += 1
                name = f"turtle{self._counter}"
                if name not in self._turtles:
                    break
        elif name in self._turtles:
            raise NameTaken(f"A turtled named [{name}] already exists")
        image = self._rng.randrange(IMAGE_COUNT)
        self._turtles[name] = _Turtle(name, x, self.height - y, theta, image)
        self.version += 1
        return name

    def kill(self, name: str) -> None:
        if name not in self._turtles:
            raise NoSuchTurtle(f"Tried to kill turtle [{name}], which does not exist")
        del self._turtles[name]
        self.version += 1

    def clear(self, background: Rgb | None = None) -> None:
        """Refill with the background colour: every trail is gone."""
        if background is not None:
            self.background = background
        self.canvas.fill(self.background)
        self.version += 1

    def reset(self, background: Rgb | None = None) -> str:
        """Remove every turtle, restart the name counter, clear, and spawn turtle1 at the centre."""
        self._turtles.clear()
        self._counter = 0
        x, y = self.centre
        name = self.spawn("", _f32(x), _f32(y), 0.0)  # turtlesim passes them as float
        self.clear(background)
        return name

    def command(self, name: str, vx: float, vy: float, w: float) -> None:
        """A velocity command (cmd_vel): forward, sideways (m/s) and turn rate (rad/s), good for
        COMMAND_TIMEOUT seconds of world time."""
        t = self._get(name)
        _finite(vx, vy, w)
        t.vx, t.vy, t.w = vx, vy, w
        t.last_command = self.time

    def set_pen(self, name: str, r: int, g: int, b: int, width: int, off: bool) -> None:
        """Pen up when `off`; else this colour and width (0 means 1 px)."""
        t = self._get(name)
        if off:
            t.pen = Pen(t.pen.color, t.pen.width, False)
        else:
            t.pen = Pen(Rgb(r, g, b), width if width else 1, True)

    def teleport_absolute(self, name: str, x: float, y: float, theta: float) -> None:
        """Jump there at the next step (drawing a line when the pen is down)."""
        _finite(x, y, theta)
        self._get(name).teleports.append(_Teleport(False, x=x, y=y, theta=theta))

    def teleport_relative(self, name: str, linear: float, angular: float) -> None:
        """Turn by `angular`, then move `linear` metres along the new heading, at the next step."""
        _finite(linear, angular)
        self._get(name).teleports.append(_Teleport(True, theta=angular, linear=linear))

    # ---------------------------------------------------------------- time

    def step(self, dt: float = UPDATE_PERIOD) -> StepReport:
        updates: list[TurtleUpdate] = []
        hits: list[WallHit] = []
        segments: list[Segment] = []
        changed = False
        for t in self._sorted():
            changed |= self._step_turtle(t, dt, updates, hits, segments)
        self.time += dt
        if changed:
            self.version += 1
        return StepReport(tuple(updates), tuple(hits), tuple(segments), changed)

    def _step_turtle(self, t: _Turtle, dt: float, updates: list[TurtleUpdate], hits: list[WallHit],
                     segments: list[Segment]) -> bool:
        modified = False
        old_theta = t.theta
        for req in t.teleports:
            old = (t.x, t.y)
            if req.relative:
                t.theta = wrap_angle(t.theta + req.theta)
                t.x += math.cos(t.theta) * req.linear
                t.y -= math.sin(t.theta) * req.linear
            else:
                t.x = req.x
                t.y = max(0.0, self.height - req.y)
                t.theta = req.theta
            self._draw(t, old, segments)
            modified = True
        t.teleports.clear()

        if self.time - t.last_command > COMMAND_TIMEOUT:
            t.vx = t.vy = t.w = 0.0

        old = (t.x, t.y)
        t.theta = wrap_angle(t.theta + t.w * dt)
        cos, sin = math.cos(t.theta), math.sin(t.theta)
        t.x += (cos * t.vx - sin * t.vy) * dt
        t.y -= (cos * t.vy + sin * t.vx) * dt

        if t.x < 0 or t.x > self.width or t.y < 0 or t.y > self.height:
            hits.append(WallHit(t.name, t.x, t.y))
        t.x = min(max(t.x, 0.0), self.width)
        t.y = min(max(t.y, 0.0), self.height)

        px = _qround(t.x * PIXELS_PER_METRE)
        py = _qround(t.y * PIXELS_PER_METRE)
        updates.append(TurtleUpdate(t.name, self._pose(t), self.canvas.pixel(px, py)))

        if t.theta != old_theta:
            modified = True
        if (t.x, t.y) != old:
            self._draw(t, old, segments)
            modified = True
        return modified

    # ---------------------------------------------------------------- helpers

    def _draw(self, t: _Turtle, old: tuple[float, float], segments: list[Segment]) -> None:
        if not t.pen.on:
            return
        m = PIXELS_PER_METRE
        self.canvas.line(old[0] * m, old[1] * m, t.x * m, t.y * m, t.pen.color, t.pen.width)
        segments.append(Segment((old[0], self.height - old[1]), (t.x, self.height - t.y), t.pen.color,
                                t.pen.width))

    def _pose(self, t: _Turtle) -> Pose:
        return Pose(t.x, self.height - t.y, t.theta, math.hypot(t.vx, t.vy), t.w)

    def _get(self, name: str) -> _Turtle:
        try:
            return self._turtles[name]
        except KeyError:
            raise NoSuchTurtle(f"no turtle named [{name}]") from None

    def _sorted(self) -> list[_Turtle]:
        return [self._turtles[n] for n in sorted(self._turtles)]


def _finite(*values: float) -> None:
    if not all(math.isfinite(v) for v in values):
        raise InvalidValue(f"values must be finite numbers, got {', '.join(repr(v) for v in values)}")


def _f32(value: float) -> float:
    return float(struct.unpack("<f", struct.pack("<f", value))[0])


def _qround(value: float) -> int:
    """Qt's qRound: halves away from zero."""
    return math.floor(value + 0.5) if value >= 0 else -math.floor(-value + 0.5)
