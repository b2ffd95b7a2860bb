"""What the navigation nodes take from outside, checked at their edge: maps, goals, initial
poses and scans. Each check returns None for a usable input, else one line saying what is
wrong; the node logs it, leaves the input out and goes on serving. A NaN let through does not
fail where it comes in: it turns a particle filter's weights into NaN for good, or fails deep
in a planner with "cannot convert float NaN to integer".

Pure: message fields in, text out. The wording of move_base's quaternion checks is its
isQuaternionValid's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

#: How far a goal's z axis may tilt from the vertical (move_base's |dot - 1| <= 1e-3).
_VERTICAL_TOLERANCE = 1e-3


def _numbers(values: Sequence[float]) -> str:
    return ", ".join(f"{value:g}" for value in values)


def map_problem(info: Any, cells: int) -> str | None:
    """Why an OccupancyGrid with this `info` (MapMetaData) and `cells` data values cannot be a
    map to localise or plan on."""
    width, height = int(info.width), int(info.height)
    if width == 0 or height == 0:
        return f"the map is {width} x {height} cells: there is no cell to localise or plan on"
    if cells != width * height:
        return f"the map says {width} x {height} cells ({width * height}) but carries {cells}"
    resolution = float(info.resolution)
    if not (math.isfinite(resolution) and resolution > 0):
        return f"the map's resolution is {resolution:g} metres a cell; it must be a positive number"
    origin = info.origin.position
    if not (math.isfinite(origin.x) and math.isfinite(origin.y)):
        return f"the map's origin ({_numbers((origin.x, origin.y))}) is not a finite position"
    return None


def quaternion_problem(q: Any) -> str | None:
    """move_base's isQuaternionValid, as the line it logs: finite, not of length 0, and turning
    the z axis (nearly) onto itself, since a robot on a map only turns about the vertical."""
    values = (q.x, q.y, q.z, q.w)
    if not all(math.isfinite(v) for v in values):
        return "Quaternion has nans or infs... discarding as a navigation goal"
    scale = max(abs(v) for v in values)  # divided out first: a component of 1e154 squares to inf
    if scale == 0.0:
        return "Quaternion has length close to zero... discarding as navigation goal"
    unit = [v / scale for v in values]
    length = math.hypot(*unit)
    if scale * length < 1e-3:
        return "Quaternion has length close to zero... discarding as navigation goal"
    x, y = unit[0] / length, unit[1] / length
    z_of_rotated_up = 1.0 - 2.0 * (x * x + y * y)  # the rotated (0, 0, 1)'s z
    if abs(z_of_rotated_up - 1.0) > _VERTICAL_TOLERANCE:
        return "Quaternion is invalid... for navigation the z-axis of the quaternion must be close to vertical."
    return None


def position_problem(p: Any) -> str | None:
    if all(math.isfinite(v) for v in (p.x, p.y, p.z)):
        return None
    return f"Position ({_numbers((p.x, p.y, p.z))}) has nans or infs... discarding as a navigation goal"


def pose_problem(pose: Any) -> str | None:
    """Why a geometry_msgs/Pose cannot be a goal or a robot's pose on the map."""
    return position_problem(pose.position) or quaternion_problem(pose.orientation)


def covariance_problem(covariance: Sequence[float]) -> str | None:
    """Why an initial pose's covariance cannot spread particles: amcl reads its x-y block and
    yaw variance, which must be finite, with non-negative variances and |xy| <= sqrt(xx yy)."""
    if len(covariance) != 36:
        return f"its covariance has {len(covariance)} values, not 36"
    xx, xy, yx, yy, aa = covariance[0], covariance[1], covariance[6], covariance[7], covariance[35]
    if not all(math.isfinite(v) for v in (xx, xy, yx, yy, aa)):
        return f"its covariance's x-y block and yaw variance ({_numbers((xx, xy, yx, yy, aa))}) are not all finite"
    if xx < 0 or yy < 0 or aa < 0:
        return f"its covariance has a negative variance (x {xx:g}, y {yy:g}, yaw {aa:g})"
    if xy != yx or abs(xy) > math.sqrt(xx) * math.sqrt(yy) * (1 + 1e-9):  # roots: 1e300 squared is inf
        return f"its covariance's x-y block ({_numbers((xx, xy, yx, yy))}) is not symmetric positive semidefinite"
    return None


def scan_problem(scan: Any, finite_range: bool = False) -> str | None:
    """Why a sensor_msgs/LaserScan's rays cannot be placed: its angles must be finite, range_min
    too, and range_max above it (inf is a scanner without a limit, unless `finite_range`: a map
    builder sizes its beams by it; readings themselves may be NaN or inf: no return)."""
    angles = (scan.angle_min, scan.angle_increment)
    if not all(math.isfinite(v) for v in angles):
        return f"its angle_min and angle_increment ({_numbers(angles)}) are not finite"
    if len(scan.ranges) > 1 and scan.angle_increment == 0:
        return f"its {len(scan.ranges)} readings share one angle (angle_increment 0)"
    limits = (scan.range_min, scan.range_max)
    if not math.isfinite(scan.range_min) or not scan.range_max > scan.range_min:
        return f"its range_min and range_max ({_numbers(limits)}) are no interval: range_max must be above range_min"
    if finite_range and math.isinf(scan.range_max):
        return "its range_max is inf: the map's beams need a length"
    return None
