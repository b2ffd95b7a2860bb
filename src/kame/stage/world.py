"""The 2-D world of kame's mobile-robot simulator: pure state and rules, no ROS, no clock.

Walls come from an occupancy grid (map_server's format: a cell at or above OCCUPIED_AT is a
wall; unknown cells are open). Robots are TurtleBot-sized discs driven like a differential
drive: a command (linear x, angular z) is followed within the robot's speed and acceleration
limits and dropped after `command_timeout` seconds of simulated time without a new one. A
robot whose next step would overlap a wall or another robot stays where it is, stops and is
`stalled` (its bumper) until a step moves it again.
Sensors: a planar laser per robot (rays cast against the grid cell by cell, all beams of all
robots at once with numpy; other robots are circles), with Gaussian noise; wheel odometry that
integrates each step's true motion through the robot's miscalibrated wheels (the drift). Randomness
comes from one seeded generator, so a world replays exactly.
Bad requests (a robot inside a wall, a NaN speed, an unknown name) raise WorldError, saying why.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from kame.stage.mapfile import Grid

OCCUPIED_AT = 65  # map_saver's default --occ: a scale-mode cell this likely is a wall too
_OPEN, _WALL, _OUTSIDE = 0, 1, 2  # the laser's view of a cell


class WorldError(ValueError):
    """A request the world refuses; the text says why."""


@dataclass(frozen=True)
class RobotModel:
    """A TurtleBot 2 (Kobuki base): footprint radius, speed and acceleration limits."""

    radius: float = 0.177
    max_linear: float = 0.7  # m/s
    max_angular: float = math.pi  # rad/s (Kobuki: 180 deg/s)
    linear_acceleration: float = 1.0  # m/s^2
    angular_acceleration: float = 6.0  # rad/s^2


@dataclass(frozen=True)
class LaserModel:
    """A planar laser; the defaults are turtlebot_gazebo's scan (the Kinect's depth image as a
    laser: 57 degrees, 640 beams, 0.45 to 10 m, 20 Hz)."""

    beams: int = 640
    angle_min: float = -0.5236
    angle_max: float = 0.5236
    range_min: float = 0.45
    range_max: float = 10.0
    rate: float = 20.0  # Hz
    noise: float = 0.0  # standard deviation of each range, metres
    mount_x: float = 0.0  # the scanner's position on the robot, metres
    mount_y: float = 0.0

    def __post_init__(self) -> None:
        if self.beams < 1:
            raise WorldError(f"a laser needs at least one beam, not {self.beams}")
        if not (0 <= self.range_min < self.range_max) or not math.isfinite(self.range_max):
            raise WorldError(f"the laser's range must satisfy 0 <= range_min < range_max "
                             f"(got {self.range_min}, {self.range_max})")
        if not (self.angle_min <= self.angle_max) or self.rate <= 0 or self.noise < 0:
            raise WorldError("the laser needs angle_min <= angle_max, a rate above 0 and noise of at least 0")

    @property
    def angle_increment(self) -> float:
        return (self.angle_max - self.angle_min) / (self.beams - 1) if self.beams > 1 else 0.0

    def angles(self) -> np.ndarray:
        return np.linspace(self.angle_min, self.angle_max, self.beams)


@dataclass(frozen=True)
class OdometryModel:
    """Wheel odometry's drift, as miscalibration: each robot's left and right wheels measure
    their travel with relative errors drawn once from N(0, linear) (so straight driving curves
    in odometry, and distances are off), its turns with one drawn from N(0, angular); the
    odometry integrates the true motion through them. Independent errors per step would average
    away within a second; a miscalibrated robot drifts as real ones do, in proportion to the way
    it has gone."""

    linear: float = 0.01
    angular: float = 0.02
    wheel_separation: float = 0.23  # Kobuki's, metres

    def __post_init__(self) -> None:
        if not (self.linear >= 0 and self.angular >= 0):
            raise WorldError(f"odometry drift must be at least 0 (got {self.linear}, {self.angular})")
        if not self.wheel_separation > 0:
            raise WorldError(f"the wheel separation must be above 0, not {self.wheel_separation}")


@dataclass(frozen=True)
class Pose:
    x: float
    y: float
    theta: float


@dataclass
class Robot:
    name: str
    pose: Pose  # ground truth, in the world (map) frame
    odom: Pose  # where odometry believes the robot is, from where it started
    linear: float = 0.0  # the speeds it is moving at
    angular: float = 0.0
    command: tuple[float, float] = (0.0, 0.0)
    command_time: float = -math.inf
    stalled: bool = False
    odometry_errors: tuple[float, float, float] = (0.0, 0.0, 0.0)  # left wheel, right wheel, turns
    start: Pose = Pose(0.0, 0.0, 0.0)  # where it was spawned: reset_positions puts it back there


@dataclass(frozen=True)
class RobotState:
    """A robot after a step: poses, speeds, whether it is stalled (the bumper)."""

    name: str
    pose: Pose
    odom: Pose
    linear: float
    angular: float
    stalled: bool


class Walls:
    """The occupied cells of a grid, and the questions the world asks of them."""

    def __init__(self, grid: Grid) -> None:
        x, y, yaw = grid.origin
        if abs(yaw) > 1e-9:
            raise WorldError(f"a map whose origin is rotated (yaw {yaw}) is not supported by the simulator")
        if grid.width == 0 or grid.height == 0:
            raise WorldError("the map has no cells")
        self.occupied = np.asarray(grid.cells, dtype=np.int16) >= OCCUPIED_AT
        self.resolution = float(grid.resolution)
        self.origin = (float(x), float(y))
        self._frame = np.pad(np.where(self.occupied, _WALL, _OPEN).astype(np.int8), 1, constant_values=_OUTSIDE)
        self._clearance = _chessboard_distance(self._frame != _OPEN)

    def add_box(self, x: float, y: float, width: float, depth: float) -> None:
        """Make the cells of an axis-aligned box (centre x, y; width along x, depth along y) walls:
        an obstacle the map does not have."""
        if not _finite(x, y, width, depth) or width <= 0 or depth <= 0:
            raise WorldError(f"a box needs a finite centre and a size above 0, not {(x, y, width, depth)}")
        rows, cols = self.occupied.shape
        centre_x = self.origin[0] + (np.arange(cols) + 0.5) * self.resolution
        centre_y = self.origin[1] + (np.arange(rows) + 0.5) * self.resolution
        inside = (np.abs(centre_x[None, :] - x) <= width / 2) & (np.abs(centre_y[:, None] - y) <= depth / 2)
        self.occupied |= inside
        self._frame = np.pad(np.where(self.occupied, _WALL, _OPEN).astype(np.int8), 1, constant_values=_OUTSIDE)
        self._clearance = _chessboard_distance(self._frame != _OPEN)

    @property
    def size(self) -> tuple[float, float]:
        """(width, height) in metres."""
        rows, cols = self.occupied.shape
        return cols * self.resolution, rows * self.resolution

    def cell_of(self, x: float, y: float) -> tuple[int, int]:
        """(column, row) of a point."""
        return (math.floor((x - self.origin[0]) / self.resolution), math.floor((y - self.origin[1]) / self.resolution))

    def is_wall(self, column: int, row: int) -> bool:
        """True for an occupied cell; the outside of the map is no wall."""
        rows, cols = self.occupied.shape
        return 0 <= column < cols and 0 <= row < rows and bool(self.occupied[row, column])

    def inside(self, x: float, y: float) -> bool:
        width, height = self.size
        return 0 <= x - self.origin[0] < width and 0 <= y - self.origin[1] < height

    def disc_hits_wall(self, x: float, y: float, radius: float) -> bool:
        """True when a disc overlaps an occupied cell (cells whose square comes within `radius`)."""
        res = self.resolution
        c0, r0 = self.cell_of(x - radius, y - radius)
        c1, r1 = self.cell_of(x + radius, y + radius)
        rows, cols = self.occupied.shape
        c0, r0, c1, r1 = max(c0, 0), max(r0, 0), min(c1, cols - 1), min(r1, rows - 1)
        if c0 > c1 or r0 > r1:
            return False
        block = self.occupied[r0:r1 + 1, c0:c1 + 1]
        if not block.any():
            return False
        columns = np.arange(c0, c1 + 1)
        row_ids = np.arange(r0, r1 + 1)
        left = self.origin[0] + columns * res
        bottom = self.origin[1] + row_ids * res
        dx = np.maximum(np.maximum(left - x, x - (left + res)), 0.0)  # to each cell's square
        dy = np.maximum(np.maximum(bottom - y, y - (bottom + res)), 0.0)
        near = (dx[None, :] ** 2 + dy[:, None] ** 2) < radius * radius
        return bool((near & block).any())

    def cast(self, x: np.ndarray, y: np.ndarray, angle: np.ndarray, range_max: float) -> np.ndarray:
        """Distance from each (x, y) along each angle to the first occupied cell (inf: none within
        range_max, or the ray left the map). Cell by cell (Amanatides and Woo's traversal), except
        that a ray in open ground leaps as far as the nearest wall's distance lets it (no cell
        within that distance can be a wall), so a long free ray takes a few steps, not hundreds."""
        stride = self._frame.shape[1]
        gx = (x - self.origin[0]) / self.resolution
        gy = (y - self.origin[1]) / self.resolution
        ix = np.clip(np.floor(gx) + 1, 0, stride - 1).astype(np.int64)  # the cells cell_of names, framed
        iy = np.clip(np.floor(gy) + 1, 0, self._frame.shape[0] - 1).astype(np.int64)
        gx, gy = gx + 1, gy + 1  # grid units of the framed grid
        dx, dy = np.cos(angle), np.sin(angle)
        with np.errstate(divide="ignore"):
            inverse_x = np.where(dx != 0, 1.0 / dx, np.inf)
            inverse_y = np.where(dy != 0, 1.0 / dy, np.inf)
        ahead_x, ahead_y = (dx > 0).astype(np.float64), (dy > 0).astype(np.float64)
        step_x, step_y = np.where(dx > 0, 1, -1), np.where(dy > 0, stride, -stride)
        flat = iy * stride + ix
        cells, clearance = self._frame.reshape(-1), self._clearance.reshape(-1)
        limit = range_max / self.resolution
        ranges = np.full(x.shape, np.inf)
        ray = np.arange(x.size)
        t = np.zeros(x.shape)  # distance travelled, in cells
        while ray.size:
            cell = cells[flat]
            hit = cell == _WALL
            if hit.any():
                ranges[ray[hit]] = t[hit] * self.resolution
            done = hit | (cell == _OUTSIDE) | (t > limit)
            if done.any():
                going = ~done
                ray, flat, t, gx, gy = ray[going], flat[going], t[going], gx[going], gy[going]
                dx, dy, inverse_x, inverse_y = dx[going], dy[going], inverse_x[going], inverse_y[going]
                ahead_x, ahead_y, step_x, step_y = ahead_x[going], ahead_y[going], step_x[going], step_y[going]
                if not ray.size:
                    break
            leap = clearance[flat] - 1.0
            leaping = leap >= 1.0
            # the cell-by-cell step: to the nearer of the next column and the next row
            column, row = flat % stride, flat // stride
            with np.errstate(invalid="ignore"):  # 0 * inf: a ray along a grid line
                exit_x = np.abs((column + ahead_x - gx) * inverse_x)
                exit_y = np.abs((row + ahead_y - gy) * inverse_y)
            exit_x = np.where(np.isnan(exit_x), np.inf, exit_x)
            exit_y = np.where(np.isnan(exit_y), np.inf, exit_y)
            along_x = exit_x < exit_y
            stepped = np.where(along_x, exit_x, exit_y)
            t = np.where(leaping, t + leap, stepped)
            landed = np.floor(gy + t * dy).astype(np.int64) * stride + np.floor(gx + t * dx).astype(np.int64)
            flat = np.where(leaping, landed, flat + np.where(along_x, step_x, step_y))
        ranges[ranges > range_max] = np.inf
        return ranges


def _chessboard_distance(blocked: np.ndarray, most: int = 64) -> np.ndarray:
    """Each cell's Chebyshev distance in cells to the nearest blocked cell (0 on one, at most
    `most`): every cell within distance - 1 of it is open. By repeated 3 x 3 erosion."""
    distance = np.zeros(blocked.shape, dtype=np.int64)
    open_ground = ~blocked
    level = 0
    while open_ground.any() and level < most:
        level += 1
        distance[open_ground] = level
        eroded = open_ground.copy()
        eroded[1:, :] &= open_ground[:-1, :]
        eroded[:-1, :] &= open_ground[1:, :]
        across = eroded.copy()
        across[:, 1:] &= eroded[:, :-1]
        across[:, :-1] &= eroded[:, 1:]
        open_ground = across
    return distance


def _finite(*values: float) -> bool:
    return all(isinstance(v, (int, float)) and math.isfinite(v) for v in values)


def _toward(current: float, target: float, most: float) -> float:
    return target if abs(target - current) <= most else current + math.copysign(most, target - current)


def _advance(pose: Pose, distance: float, turn: float) -> Pose:
    """The pose after driving `distance` along an arc turning by `turn` (exact for constant speeds)."""
    if abs(turn) < 1e-9:
        x = pose.x + distance * math.cos(pose.theta)
        y = pose.y + distance * math.sin(pose.theta)
    else:
        radius = distance / turn
        x = pose.x + radius * (math.sin(pose.theta + turn) - math.sin(pose.theta))
        y = pose.y - radius * (math.cos(pose.theta + turn) - math.cos(pose.theta))
    theta = math.atan2(math.sin(pose.theta + turn), math.cos(pose.theta + turn))
    return Pose(x, y, theta)


@dataclass
class World:
    walls: Walls
    robot_model: RobotModel = field(default_factory=RobotModel)
    laser: LaserModel = field(default_factory=LaserModel)
    odometry: OdometryModel = field(default_factory=OdometryModel)
    command_timeout: float = 0.5  # seconds of simulated time
    seed: int = 0
    time: float = 0.0

    def __post_init__(self) -> None:
        if not (self.command_timeout > 0):
            raise WorldError(f"the command timeout must be above 0, not {self.command_timeout}")
        self._robots: dict[str, Robot] = {}
        self._rng = np.random.default_rng(self.seed)

    # ---------------------------------------------------------------- robots

    def names(self) -> list[str]:
        return list(self._robots)

    def _robot(self, name: str) -> Robot:
        try:
            return self._robots[name]
        except KeyError:
            raise WorldError(f"no robot named [{name}]") from None

    def _blocked(self, name: str, x: float, y: float) -> str | None:
        """Why a robot cannot stand at (x, y), or None."""
        radius = self.robot_model.radius
        if not self.walls.inside(x, y):
            return "outside the map"
        if self.walls.disc_hits_wall(x, y, radius):
            return "inside a wall"
        for other in self._robots.values():
            if other.name != name and math.hypot(other.pose.x - x, other.pose.y - y) < 2 * radius:
                return f"on robot [{other.name}]"
        return None

    def add_box(self, x: float, y: float, width: float, depth: float) -> None:
        """Place a box (Walls.add_box) while the world runs; refused if it would cover a robot,
        which could then neither move nor be seen to be inside it."""
        radius = self.robot_model.radius
        for robot in self._robots.values():
            if (abs(robot.pose.x - x) < width / 2 + radius) and (abs(robot.pose.y - y) < depth / 2 + radius):
                raise WorldError(f"a box at ({x:g}, {y:g}) of {width:g} x {depth:g} m would cover robot [{robot.name}]")
        self.walls.add_box(x, y, width, depth)

    def spawn(self, name: str, x: float, y: float, theta: float) -> RobotState:
        if not name:
            raise WorldError("a robot needs a name")
        if name in self._robots:
            raise WorldError(f"a robot named [{name}] already exists")
        if not _finite(x, y, theta):
            raise WorldError(f"cannot place [{name}] at a pose that is not finite ({x}, {y}, {theta})")
        reason = self._blocked(name, x, y)
        if reason is not None:
            raise WorldError(f"cannot place [{name}] at ({x:.3f}, {y:.3f}): {reason}")
        theta = math.atan2(math.sin(theta), math.cos(theta))
        left, right, turns = self._rng.normal(0.0, 1.0, 3) * (self.odometry.linear, self.odometry.linear,
                                                                self.odometry.angular)
        start = Pose(float(x), float(y), theta)
        robot = Robot(name, start, Pose(0.0, 0.0, 0.0), odometry_errors=(float(left), float(right), float(turns)),
                      start=start)
        self._robots[name] = robot
        return self._state(robot)

    def reset_positions(self) -> list[RobotState]:
        """Every robot back where it was spawned, as stageros's reset_positions: ground truth at
        its start pose, odometry at its origin again, at rest and no longer stalled. Its command
        stays (Stage's SetPose leaves the speed set): a driver still publishing drives on, one
        that stopped is timed out as before. The wheels keep their miscalibration: the same robot.
        A start pose is not checked again (Stage does not either): a box placed there since
        leaves the robot inside it, stalled on its first move."""
        for robot in self._robots.values():
            robot.pose, robot.odom = robot.start, Pose(0.0, 0.0, 0.0)
            robot.linear = robot.angular = 0.0
            robot.stalled = False
        return [self._state(r) for r in self._robots.values()]

    def remove(self, name: str) -> None:
        self._robot(name)
        del self._robots[name]

    def command(self, name: str, linear: float, angular: float) -> None:
        """A velocity command (cmd_vel's linear.x and angular.z), followed until the timeout."""
        robot = self._robot(name)
        if not _finite(linear, angular):
            raise WorldError(f"refusing a velocity that is not finite (linear {linear}, angular {angular})")
        robot.command = (float(linear), float(angular))
        robot.command_time = self.time

    def robot(self, name: str) -> RobotState:
        return self._state(self._robot(name))

    @staticmethod
    def _state(robot: Robot) -> RobotState:
        return RobotState(robot.name, robot.pose, robot.odom, robot.linear, robot.angular, robot.stalled)

    # ---------------------------------------------------------------- time

    def step(self, dt: float) -> list[RobotState]:
        """Advance `dt` seconds: each robot follows its command, moves unless it would collide,
        and its odometry integrates the motion with drift."""
        if not (dt > 0 and math.isfinite(dt)):
            raise WorldError(f"a step must last a finite time above 0, not {dt}")
        model = self.robot_model
        for robot in self._robots.values():
            fresh = self.time - robot.command_time <= self.command_timeout
            want_linear, want_angular = robot.command if fresh else (0.0, 0.0)
            want_linear = max(-model.max_linear, min(model.max_linear, want_linear))
            want_angular = max(-model.max_angular, min(model.max_angular, want_angular))
            robot.linear = _toward(robot.linear, want_linear, model.linear_acceleration * dt)
            robot.angular = _toward(robot.angular, want_angular, model.angular_acceleration * dt)
            distance, turn = robot.linear * dt, robot.angular * dt
            if not (distance or turn):
                continue  # at rest: a robot stopped by a wall stays stalled until it drives away
            moved = _advance(robot.pose, distance, turn)
            if self._blocked(robot.name, moved.x, moved.y) is not None:
                robot.linear = robot.angular = 0.0
                robot.stalled = True
                continue
            robot.stalled = False
            robot.pose = moved
            robot.odom = self._odometry_step(robot, distance, turn)
        self.time += dt
        return [self._state(r) for r in self._robots.values()]

    def _odometry_step(self, robot: Robot, distance: float, turn: float) -> Pose:
        """The odometry after a true motion, as the robot's miscalibrated wheels measure it."""
        half = turn * self.odometry.wheel_separation / 2
        left_error, right_error, turn_error = robot.odometry_errors
        left, right = (distance - half) * (1 + left_error), (distance + half) * (1 + right_error)
        measured_turn = (right - left) / self.odometry.wheel_separation * (1 + turn_error)
        return _advance(robot.odom, (left + right) / 2, measured_turn)

    # ---------------------------------------------------------------- the laser

    def scans(self, names: Iterable[str] | None = None) -> dict[str, np.ndarray]:
        """Each robot's laser ranges (LaserScan's: inf for no return within range, -inf for a
        return nearer than range_min), all beams of all robots cast at once."""
        chosen = [self._robot(n) for n in (self.names() if names is None else names)]
        if not chosen:
            return {}
        laser = self.laser
        angles = laser.angles()
        beams = len(angles)
        poses = np.array([(r.pose.x, r.pose.y, r.pose.theta) for r in chosen])
        cos_t, sin_t = np.cos(poses[:, 2]), np.sin(poses[:, 2])
        origin_x = poses[:, 0] + cos_t * laser.mount_x - sin_t * laser.mount_y
        origin_y = poses[:, 1] + sin_t * laser.mount_x + cos_t * laser.mount_y
        ray_x = np.repeat(origin_x, beams)
        ray_y = np.repeat(origin_y, beams)
        ray_angle = (poses[:, 2:3] + angles[None, :]).reshape(-1)
        ranges = self.walls.cast(ray_x, ray_y, ray_angle, laser.range_max)
        owner = np.repeat(np.arange(len(chosen)), beams)
        ranges = np.minimum(ranges, self._robot_hits(ray_x, ray_y, ray_angle, owner, chosen))
        ranges[ranges > laser.range_max] = np.inf
        if laser.noise > 0:
            finite = np.isfinite(ranges)
            ranges[finite] += self._rng.normal(0.0, laser.noise, int(finite.sum()))
            ranges[finite] = np.clip(ranges[finite], 0.0, laser.range_max)
        ranges[ranges < laser.range_min] = -np.inf
        return {robot.name: ranges[i * beams:(i + 1) * beams] for i, robot in enumerate(chosen)}

    def _robot_hits(self, x: np.ndarray, y: np.ndarray, angle: np.ndarray, owner: np.ndarray,
                    casting: list[Robot]) -> np.ndarray:
        """Distance along each ray to the nearest other robot's disc (inf when none)."""
        best = np.full(x.shape, np.inf)
        radius = self.robot_model.radius
        dx, dy = np.cos(angle), np.sin(angle)
        casting_names = np.array([r.name for r in casting])
        for other in self._robots.values():
            ox, oy = other.pose.x - x, other.pose.y - y
            along = ox * dx + oy * dy
            gap2 = ox * ox + oy * oy - along * along
            half = np.sqrt(np.maximum(radius * radius - gap2, 0.0))
            t = along - half
            seen = (gap2 < radius * radius) & (t > 0) & (casting_names[owner] != other.name)
            best = np.where(seen, np.minimum(best, t), best)
        return best
