"""gmapping's filter (kame.nav.slam) on the office world, without ROS: a scripted drive with
drifting odometry builds a map that matches the ground truth's.

The metric and its thresholds: tests/nav/mapscore.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from kame.nav.slam import Gmapping, GmappingParams
from kame.stage.world import LaserModel, OdometryModel, Walls, World
from tests.nav.mapscore import AGREEMENT, DRAWN_NEAR_WALLS, WALLS_DRAWN, score
from tests.nav.test_amcl import OFFICE_DRIVE
from tests.nav.worlds import load_world_map

# turtlebot_navigation's gmapping values (launch/includes/gmapping/gmapping.launch.xml), with 30
# particles (gmapping's default) where the TurtleBot's take 80, to keep the test short
TURTLEBOT = GmappingParams(maxUrange=6.0, maxRange=8.0, minimumScore=200, srr=0.01, srt=0.02, str=0.01, stt=0.02,
                           linearUpdate=0.5, angularUpdate=0.436, particles=30, xmin=-1.0, ymin=-1.0, xmax=1.0,
                           ymax=1.0)


def build_map(drift: OdometryModel, seed: int, filter_seed: int) -> tuple[Gmapping, World]:
    """OFFICE_DRIVE with a scan every 0.1 s (the TurtleBot's 10 Hz and more)."""
    world = World(Walls(load_world_map("office")), laser=LaserModel(noise=0.01), odometry=drift, seed=seed)
    world.spawn("bot", 0.0, 0.0, 0.0)
    slam = Gmapping(TURTLEBOT, seed=filter_seed)
    laser = world.laser
    for linear, angular, seconds in OFFICE_DRIVE:
        for step in range(round(seconds / 0.05)):
            world.command("bot", linear, angular)
            world.step(0.05)
            if step % 2:
                odom = world.robot("bot").odom
                slam.add_scan((odom.x, odom.y, odom.theta), world.scans(["bot"])["bot"], laser.angles(),
                              laser.range_max, world.time)
    return slam, world


# Seeded, so each run is the same; bench/slam_office.py runs the drive over many seeds, and
# bench/RESULTS.md gives how often the map passes there (not every seed does).
@pytest.mark.parametrize(("drift", "seed", "filter_seed"), [(OdometryModel(), 4, 4), (OdometryModel(0.03, 0.05), 5, 2)],
                         ids=["stageros-drift", "three-times-the-drift"])
def test_the_built_map_matches_the_office(drift: OdometryModel, seed: int, filter_seed: int) -> None:
    slam, world = build_map(drift, seed, filter_seed)
    found = score(slam.occupancy(), load_world_map("office"))
    assert found.known > 20000  # the corridor and two rooms: a quarter of the office
    assert found.agreement >= AGREEMENT
    assert found.drawn_near_walls >= DRAWN_NEAR_WALLS
    assert found.walls_drawn >= WALLS_DRAWN
    robot = world.robot("bot")
    x, y, theta = slam.best_pose()
    slam_error = math.dist((x, y), (robot.pose.x, robot.pose.y))
    assert slam_error < 0.15
    assert abs(math.degrees(math.remainder(theta - robot.pose.theta, 2 * math.pi))) < 5
    assert math.dist((robot.odom.x, robot.odom.y), (robot.pose.x, robot.pose.y)) > 5 * slam_error
    assert slam.scans_processed > 40 and slam.resamples >= 1


def test_the_odometry_alone_draws_a_worse_map() -> None:
    """The metric tells a map built on odometry alone (the matcher off, one particle, no noise)
    from gmapping's: the same drive, the same drift, fails it."""
    blind = GmappingParams(**{**TURTLEBOT.__dict__, "particles": 1, "minimumScore": 1e9, "srr": 0.0, "srt": 0.0,
                              "str": 0.0, "stt": 0.0})
    world = World(Walls(load_world_map("office")), laser=LaserModel(noise=0.01), odometry=OdometryModel(), seed=4)
    world.spawn("bot", 0.0, 0.0, 0.0)
    slam = Gmapping(blind)
    for linear, angular, seconds in OFFICE_DRIVE:
        for step in range(round(seconds / 0.05)):
            world.command("bot", linear, angular)
            world.step(0.05)
            if step % 2:
                odom = world.robot("bot").odom
                slam.add_scan((odom.x, odom.y, odom.theta), world.scans(["bot"])["bot"], world.laser.angles(),
                              world.laser.range_max)
    found = score(slam.occupancy(), load_world_map("office"))
    assert found.drawn_near_walls < DRAWN_NEAR_WALLS or found.walls_drawn < WALLS_DRAWN


def test_the_grid_grows_and_reports_at_least_its_bounds() -> None:
    slam = Gmapping(GmappingParams(particles=2, xmin=-1.0, ymin=-1.0, xmax=1.0, ymax=1.0, maxUrange=4.0))
    empty = slam.occupancy()
    assert empty.cells.shape == (40, 40) and (empty.cells == -1).all() and empty.origin == pytest.approx((-1.0, -1.0))
    angles = np.linspace(-0.5, 0.5, 50)
    slam.add_scan((0.0, 0.0, 0.0), np.full(50, 3.0), angles, 10.0)
    view = slam.occupancy()
    assert view.origin[0] <= -1.0 and view.origin[0] + view.cells.shape[1] * view.resolution >= 3.0
    wall_x = view.origin[0] + (np.nonzero((view.cells == 100).any(axis=0))[0] + 0.5) * view.resolution
    assert wall_x.min() > 2.5 and wall_x.max() < 3.2  # the end points, about 3 m ahead
    free = view.cells == 0
    assert free.sum() > 100 and (view.cells == -1).sum() > 0


def test_bad_parameters_say_why() -> None:
    with pytest.raises(ValueError, match="particles"):
        GmappingParams(particles=0)
    with pytest.raises(ValueError, match="xmin < xmax"):
        GmappingParams(xmin=1.0, xmax=-1.0)
