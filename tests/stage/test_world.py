"""The 2-D world: driving within limits, the command timeout, collisions, odometry's drift and
the laser checked against the grid cell by cell."""

from __future__ import annotations

import math

import numpy as np
import pytest

from kame.stage.mapfile import Grid
from kame.stage.world import LaserModel, OdometryModel, Pose, Walls, World, WorldError

RES = 0.05


def room(size: int = 100, pillar: bool = True) -> Grid:
    """A walled square room (size x size cells of 5 cm), with a pillar off centre."""
    cells = np.zeros((size, size), dtype=np.int8)
    cells[0, :] = cells[-1, :] = cells[:, 0] = cells[:, -1] = 100
    if pillar:
        cells[60:70, 30:36] = 100
    cells[10, 10] = -1  # unknown is open ground
    return Grid(cells, RES, (-1.0, -1.0, 0.0))


def drive(world: World, name: str, linear: float, angular: float, seconds: float, dt: float = 0.01) -> None:
    for i in range(round(seconds / dt)):
        if i % 10 == 0:
            world.command(name, linear, angular)
        world.step(dt)


def test_driving_straight_follows_the_acceleration_limit() -> None:
    world = World(Walls(room(pillar=False)), odometry=OdometryModel(0.0, 0.0))
    world.spawn("bot", 0.0, 1.0, 0.0)
    drive(world, "bot", 0.5, 0.0, 1.0)
    state = world.robot("bot")
    assert state.linear == pytest.approx(0.5)
    assert state.pose.x == pytest.approx(0.5 - 0.5 * 0.5 / 1.0 / 2 * 1.0, abs=0.01)  # ramp then cruise
    assert state.odom.x == pytest.approx(state.pose.x - 0.0) and state.odom.y == pytest.approx(0.0)


def test_speeds_are_limited_and_turning_is_exact() -> None:
    world = World(Walls(room(pillar=False)), odometry=OdometryModel(0.0, 0.0))
    world.spawn("bot", 1.5, 1.5, 0.0)
    drive(world, "bot", 0.0, 100.0, 2.0)
    assert world.robot("bot").angular == pytest.approx(math.pi)
    assert (world.robot("bot").pose.x, world.robot("bot").pose.y) == (1.5, 1.5)


def test_the_command_times_out() -> None:
    world = World(Walls(room(pillar=False)), command_timeout=0.5)
    world.spawn("bot", 0.0, 1.0, 0.0)
    world.command("bot", 0.3, 0.0)
    for _ in range(100):
        world.step(0.01)
    assert world.robot("bot").linear == 0.0
    x = world.robot("bot").pose.x
    world.step(0.01)
    assert world.robot("bot").pose.x == x > 0.1


def test_a_wall_stops_the_robot_and_the_bumper_says_so() -> None:
    world = World(Walls(room(pillar=False)))
    world.spawn("bot", 3.0, 1.0, 0.0)
    drive(world, "bot", 0.5, 0.0, 3.0)
    state = world.robot("bot")
    assert state.stalled and state.linear == 0.0
    wall_x = -1.0 + 99 * RES
    assert wall_x - 0.177 - 0.02 < state.pose.x < wall_x - 0.177
    for _ in range(100):  # the command times out: at rest against the wall, the bumper stays pressed
        world.step(0.01)
    assert world.robot("bot").stalled
    drive(world, "bot", -0.2, 0.0, 0.5)
    assert not world.robot("bot").stalled and world.robot("bot").pose.x < state.pose.x


def test_robots_collide_with_each_other() -> None:
    world = World(Walls(room(pillar=False)))
    world.spawn("a", 0.0, 1.0, 0.0)
    world.spawn("b", 1.0, 1.0, 0.0)
    drive(world, "a", 0.5, 0.0, 3.0)
    a = world.robot("a")
    assert a.stalled and 1.0 - 2 * 0.177 - 0.02 < a.pose.x < 1.0 - 2 * 0.177


def test_odometry_drifts_from_the_truth_reproducibly() -> None:
    def straight(seed: int) -> tuple[float, float, float]:
        world = World(Walls(room(pillar=False)), odometry=OdometryModel(0.02, 0.03), seed=seed)
        world.spawn("bot", -0.5, 0.0, 0.0)
        drive(world, "bot", 0.5, 0.0, 4.0)
        state = world.robot("bot")
        assert state.pose.y == 0.0 and state.pose.theta == 0.0
        return state.pose.x + 0.5, state.odom.x, state.odom.theta

    truth, believed, heading = straight(1)
    assert truth == pytest.approx(0.125 + 0.5 * 3.5, abs=0.01)  # half a second of acceleration, then cruising
    assert believed != truth and abs(believed - truth) < 0.1 * truth
    assert heading != 0.0 and abs(heading) < 0.5  # unequal wheels: straight driving curves in odometry
    assert straight(1) == (truth, believed, heading) and straight(2)[1:] != (believed, heading)
    exact = World(Walls(room(pillar=False)), odometry=OdometryModel(0.0, 0.0))
    exact.spawn("bot", 0.0, 0.0, 0.0)
    drive(exact, "bot", 0.3, 0.5, 4.0)
    state = exact.robot("bot")
    assert state.odom.x == pytest.approx(state.pose.x) and state.odom.theta == pytest.approx(state.pose.theta)


def test_reset_positions_puts_every_robot_back_as_at_start() -> None:
    """stageros's reset_positions: truth at the start pose, odometry at its origin, at rest, the
    bumper released; a command still fresh is followed on from there, as Stage's SetPose leaves
    the speed set; the odometry drifts as before (the same wheels)."""
    world = World(Walls(room(pillar=False)), odometry=OdometryModel(0.02, 0.03), seed=3)
    world.spawn("a", 3.0, 1.0, 0.0)
    world.spawn("b", 0.0, -0.5, math.pi / 2)
    drive(world, "a", 0.5, 0.0, 3.0)  # into the east wall
    drive(world, "b", 0.4, 0.6, 2.0)
    assert world.robot("a").stalled and world.robot("b").odom != world.robot("b").pose
    states = {s.name: s for s in world.reset_positions()}
    assert states["a"].pose == Pose(3.0, 1.0, 0.0) and states["b"].pose == Pose(0.0, -0.5, math.pi / 2)
    for state in states.values():
        assert state.odom == Pose(0.0, 0.0, 0.0) and (state.linear, state.angular, state.stalled) == (0.0, 0.0, False)
    before = world.robot("b").odom
    world.command("b", 0.4, 0.0)
    world.step(0.1)
    moved = world.robot("b")
    assert moved.pose.y > -0.5 and moved.odom != before and moved.odom.x != moved.pose.y + 0.5  # still drifting


@pytest.mark.parametrize(("x", "y", "why"), [
    (-0.95, 0.0, "inside a wall"), (0.6, 2.3, "inside a wall"), (9.0, 0.0, "outside the map"),
    (math.nan, 0.0, "not finite"),
])
def test_robots_cannot_be_placed_in_walls(x: float, y: float, why: str) -> None:
    world = World(Walls(room()))
    with pytest.raises(WorldError, match=why):
        world.spawn("bot", x, y, 0.0)


def test_bad_requests_are_refused() -> None:
    world = World(Walls(room()))
    world.spawn("bot", 0.0, 0.0, 0.0)
    with pytest.raises(WorldError, match="already exists"):
        world.spawn("bot", 1.0, 1.0, 0.0)
    with pytest.raises(WorldError, match="on robot"):
        world.spawn("other", 0.1, 0.0, 0.0)
    for linear, angular in ((math.nan, 0.0), (0.0, math.inf)):
        with pytest.raises(WorldError, match="not finite"):
            world.command("bot", linear, angular)
    with pytest.raises(WorldError, match="no robot named"):
        world.command("ghost", 0.1, 0.0)
    with pytest.raises(WorldError):
        world.step(math.nan)
    with pytest.raises(WorldError, match="rotated"):
        Walls(Grid(np.zeros((3, 3), np.int8), RES, (0.0, 0.0, 0.5)))
    with pytest.raises(WorldError):
        LaserModel(range_min=5.0, range_max=1.0)


def _cells_along(walls: Walls, x: float, y: float, angle: float, distance: float) -> list[tuple[int, int]]:
    """Every cell a segment passes through, found by fine sampling (independent of the caster)."""
    samples = np.linspace(0.0, distance, max(2, int(distance / (RES / 50))))
    cells = []
    for t in samples:
        cell = walls.cell_of(x + t * math.cos(angle), y + t * math.sin(angle))
        if not cells or cells[-1] != cell:
            cells.append(cell)
    return cells


@pytest.mark.parametrize(("x", "y", "theta"), [(0.3, 0.4, 0.3), (2.0, 2.5, -2.0), (-0.5, 3.5, 1.0)])
def test_the_laser_sees_the_walls_where_the_map_says(x: float, y: float, theta: float) -> None:
    world = World(Walls(room()), laser=LaserModel(beams=181, angle_min=-math.pi, angle_max=math.pi, range_min=0.1))
    world.spawn("bot", x, y, theta)
    ranges = world.scans()["bot"]
    walls = world.walls
    angles = theta + world.laser.angles()
    assert np.isfinite(ranges).all()  # a closed room
    for angle, distance in zip(angles, ranges, strict=True):
        before = _cells_along(walls, x, y, angle, distance - 1e-6)
        assert not any(walls.is_wall(*cell) for cell in before), (angle, distance)
        end = walls.cell_of(x + (distance + 1e-6) * math.cos(angle), y + (distance + 1e-6) * math.sin(angle))
        assert walls.is_wall(*end), (angle, distance)


def test_rays_among_scattered_walls_stop_at_the_first_wall_cell() -> None:
    rng = np.random.default_rng(5)
    cells = np.where(rng.random((80, 120)) < 0.03, 100, 0).astype(np.int8)
    cells[20:60, 40:80] = 0  # an open hall, where rays leap
    cells[39, 10:110] = 100  # a long wall along a row
    walls = Walls(Grid(cells, RES, (-2.0, -1.0, 0.0)))
    # none on a diagonal through grid corners: there either neighbouring cell is a right answer
    origins = [(0.01, 1.02), (1.0, 0.5), (2.5, 0.3), (-1.7, 2.6), (0.512, 0.95 - 1e-9)]
    angles = np.concatenate([np.linspace(-math.pi, math.pi, 61), [0.0, math.pi / 2, math.pi, -math.pi / 2]])
    for x, y in origins:
        if walls.is_wall(*walls.cell_of(x, y)):
            continue
        ranges = walls.cast(np.full(angles.shape, x), np.full(angles.shape, y), angles, 8.0)
        for angle, distance in zip(angles, ranges, strict=True):
            if not np.isfinite(distance):  # left the map or beyond 8 m: every cell on the way is open
                assert not any(walls.is_wall(*c) for c in _cells_along(walls, x, y, angle, 8.0)), (x, y, angle)
                continue
            before = _cells_along(walls, x, y, angle, distance - 1e-6)
            assert not any(walls.is_wall(*cell) for cell in before), (x, y, angle, distance)
            end = walls.cell_of(x + (distance + 1e-6) * math.cos(angle), y + (distance + 1e-6) * math.sin(angle))
            assert walls.is_wall(*end), (x, y, angle, distance)


def test_the_laser_sees_other_robots_its_limits_and_noise() -> None:
    laser = LaserModel(beams=3, angle_min=-0.1, angle_max=0.1, range_min=0.45, range_max=1.5)
    world = World(Walls(room(pillar=False)), laser=laser)
    world.spawn("a", 0.0, 1.0, 0.0)
    world.spawn("b", 1.0, 1.0, math.pi)
    assert world.scans()["a"][1] == pytest.approx(1.0 - 0.177)
    assert world.scans()["b"][1] == pytest.approx(1.0 - 0.177)
    world.remove("b")
    assert np.isposinf(world.scans()["a"]).all()  # the wall is 2.95 m away, beyond range_max
    world.spawn("near", 0.5, 1.0, 0.0)
    assert np.isneginf(world.scans()["a"][1])  # nearer than range_min
    noisy = World(Walls(room(pillar=False)), laser=LaserModel(beams=50, noise=0.01), seed=3)
    noisy.spawn("a", 0.0, 0.0, 0.0)
    quiet = World(Walls(room(pillar=False)), laser=LaserModel(beams=50))
    quiet.spawn("a", 0.0, 0.0, 0.0)
    difference = noisy.scans()["a"] - quiet.scans()["a"]
    assert 0.002 < float(np.std(difference)) < 0.03


def test_a_box_added_to_the_walls_is_seen_and_bumped_into() -> None:
    walls = Walls(room(pillar=False))
    walls.add_box(1.0, 1.5, 0.4, 0.2)  # x 0.8..1.2, y 1.4..1.6
    assert walls.is_wall(*walls.cell_of(1.0, 1.5)) and walls.is_wall(*walls.cell_of(1.15, 1.45))
    assert not walls.is_wall(*walls.cell_of(1.3, 1.5)) and not walls.is_wall(*walls.cell_of(1.0, 1.7))
    world = World(walls, laser=LaserModel(beams=1, angle_min=0.0, angle_max=0.0, range_min=0.1, noise=0.0))
    world.spawn("bot", 0.0, 1.5, 0.0)
    assert world.scans()["bot"][0] == pytest.approx(0.8, abs=RES)  # the laser stops at the box's face
    drive(world, "bot", 0.3, 0.0, 5.0)
    robot = world.robot("bot")
    assert robot.stalled and robot.pose.x < 0.8 - 0.17  # stopped by the box, not through it
    for bad in ((1.0, 1.0, 0.0, 0.2), (math.nan, 1.0, 0.2, 0.2)):
        with pytest.raises(WorldError):
            walls.add_box(*bad)
