"""The navigation nodes' checks of what comes in (kame.nav.inputs), on message objects."""

from __future__ import annotations

import math

import pytest

from geometry_msgs.msg import Pose, PoseWithCovariance
from kame.nav import inputs
from nav_msgs.msg import MapMetaData
from sensor_msgs.msg import LaserScan

NAN, INF = math.nan, math.inf


def info(width: int, height: int, resolution: float = 0.05, x: float = 0.0) -> MapMetaData:
    meta = MapMetaData(width=width, height=height, resolution=resolution)
    meta.origin.position.x = x
    return meta


@pytest.mark.parametrize(("meta", "cells", "problem"), [
    (info(0, 0), 0, "the map is 0 x 0 cells: there is no cell to localise or plan on"),
    (info(3, 2), 5, "the map says 3 x 2 cells (6) but carries 5"),
    (info(3, 2, resolution=0.0), 6, "the map's resolution is 0 metres a cell; it must be a positive number"),
    (info(3, 2, resolution=NAN), 6, "the map's resolution is nan metres a cell; it must be a positive number"),
    (info(3, 2, x=INF), 6, "the map's origin (inf, 0) is not a finite position"),
    (info(3, 2), 6, None),
])
def test_maps(meta: MapMetaData, cells: int, problem: str | None) -> None:
    assert inputs.map_problem(meta, cells) == problem


def pose(x: float = 0.0, qx: float = 0.0, qz: float = 0.0, qw: float = 1.0) -> Pose:
    p = Pose()
    p.position.x = x
    p.orientation.x, p.orientation.z, p.orientation.w = qx, qz, qw
    return p


@pytest.mark.parametrize(("goal", "problem"), [
    (pose(x=NAN), "Position (nan, 0, 0) has nans or infs... discarding as a navigation goal"),
    (pose(qz=INF), "Quaternion has nans or infs... discarding as a navigation goal"),
    (pose(qw=0.0), "Quaternion has length close to zero... discarding as navigation goal"),
    (pose(qx=1.0, qw=0.0), "Quaternion is invalid... for navigation the z-axis of the quaternion must be close to "
                           "vertical."),
    (pose(qz=2.0, qw=2.0), None),  # not normalised: move_base normalises it
    (pose(qx=1.3407807929942597e154), "Quaternion is invalid... for navigation the z-axis of the quaternion must be "
                                      "close to vertical."),  # its square is inf: found by tests/fuzz
])
def test_goals_as_move_base_checks_their_quaternions(goal: Pose, problem: str | None) -> None:
    assert inputs.pose_problem(goal) == problem


def covariance(xx: float = 0.25, xy: float = 0.0, yy: float = 0.25, aa: float = 0.07) -> list[float]:
    values = [0.0] * 36
    values[0], values[1], values[6], values[7], values[35] = xx, xy, xy, yy, aa
    return values


@pytest.mark.parametrize(("values", "problem"), [
    (covariance(xx=NAN), "its covariance's x-y block and yaw variance (nan, 0, 0, 0.25, 0.07) are not all finite"),
    (covariance(aa=-1.0), "its covariance has a negative variance (x 0.25, y 0.25, yaw -1)"),
    (covariance(xy=1.0), "its covariance's x-y block (0.25, 1, 1, 0.25) is not symmetric positive semidefinite"),
    (covariance(xx=1e300, xy=1e301, yy=1e300),
     "its covariance's x-y block (1e+300, 1e+301, 1e+301, 1e+300) is not symmetric positive semidefinite"),
    (covariance(), None),
    (PoseWithCovariance().covariance, None),  # all zero: the particles on the pose itself
])
def test_initial_pose_covariances(values: list[float], problem: str | None) -> None:
    assert inputs.covariance_problem(values) == problem


@pytest.mark.parametrize(("scan", "problem"), [
    (LaserScan(angle_increment=NAN, range_max=10.0, ranges=[1.0, 2.0]),
     "its angle_min and angle_increment (0, nan) are not finite"),
    (LaserScan(angle_increment=0.0, range_max=10.0, ranges=[1.0, 2.0]),
     "its 2 readings share one angle (angle_increment 0)"),
    (LaserScan(angle_increment=0.1, range_min=1.0, range_max=NAN, ranges=[1.0]),
     "its range_min and range_max (1, nan) are no interval: range_max must be above range_min"),
    (LaserScan(angle_increment=0.1, range_max=INF, ranges=[NAN, INF, 1.0]), None),
])
def test_scans(scan: LaserScan, problem: str | None) -> None:
    assert inputs.scan_problem(scan) == problem


def test_a_map_builder_needs_a_finite_range_max() -> None:
    scan = LaserScan(angle_increment=0.1, range_max=INF, ranges=[1.0])
    assert inputs.scan_problem(scan, finite_range=True) == "its range_max is inf: the map's beams need a length"
