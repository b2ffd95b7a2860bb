"""depthimage_to_laserscan's conversion against geometry: a pinhole camera facing a flat wall, a
wall at an angle, a post nearer than the wall, and upstream's rules for NaN, Inf, 16UC1 and
scan_height."""

from __future__ import annotations

import math

import numpy as np
import pytest

from kame.depthimage_to_laserscan.conversion import (
    ConversionError,
    Projection,
    Settings,
    convert,
    depth_in_meters,
)

WIDTH, HEIGHT = 640, 480
FX = 554.25  # Gazebo's Kinect: a 1.047 rad horizontal field of view over 640 pixels
LENS = Projection(fx=FX, fy=FX, cx=(WIDTH - 1) / 2, cy=(HEIGHT - 1) / 2)


def wall_depth(z: float) -> np.ndarray:
    """A flat wall facing the camera at distance z: every pixel's depth is z."""
    return np.full((HEIGHT, WIDTH), z)


def beam_angles(scan_angle_min: float, increment: float) -> np.ndarray:
    return scan_angle_min + increment * np.arange(WIDTH)


def column_angle(u: int) -> float:
    """The scan angle of an image column: left of the image is positive (counter-clockwise)."""
    return -math.atan((u - LENS.cx) / FX)


def beams_between(low: float, high: float) -> np.ndarray:
    scan_min = -math.atan(LENS.cx / FX)
    angles = beam_angles(scan_min, 2 * -scan_min / (WIDTH - 1))
    return np.flatnonzero((angles > low) & (angles < high))


def test_a_facing_wall_reads_its_distance_over_the_cosine_of_each_beam() -> None:
    scan = convert(wall_depth(2.0), LENS, Settings(scan_height=10, range_max=10.0))
    half_fov = math.atan(LENS.cx / FX)
    assert scan.angle_max == pytest.approx(half_fov) and scan.angle_min == pytest.approx(-half_fov)
    angles = beam_angles(scan.angle_min, scan.angle_increment)
    assert scan.ranges[WIDTH // 2] == pytest.approx(2.0 / math.cos(angles[WIDTH // 2]), abs=1e-4)
    finite = np.isfinite(scan.ranges)
    # upstream bins each pixel by its own angle, which is not linear in the column: in the
    # middle, where a pixel spans more than a beam, some beams get none (NaN), and a beam's
    # range is its pixel's, up to one increment off the beam's nominal angle
    assert finite.sum() > 0.9 * WIDTH
    assert np.allclose(scan.ranges[finite], 2.0 / np.cos(angles[finite]), atol=3e-3)


def test_beams_turn_the_other_way_from_the_image_columns() -> None:
    depth = wall_depth(3.0)
    depth[:, :WIDTH // 4] = 1.0  # a near post on the image's left is on the scan's left: high angles
    scan = convert(depth, LENS, Settings(scan_height=1))
    angles = beam_angles(scan.angle_min, scan.angle_increment)
    near = np.isfinite(scan.ranges) & (scan.ranges < 1.5)
    post_edge = column_angle(WIDTH // 4 - 1)
    assert near.any() and (angles[near] >= post_edge - 2e-3).all()  # within a beam of the post's edge


def test_a_slanted_wall_matches_the_ray_intersection() -> None:
    # the wall x = 1.5 in the optical frame's x-z plane... rotated: z = 2 + 0.5 * x (a plane seen slanted)
    columns = np.arange(WIDTH)
    x_per_z = (columns - LENS.cx) / FX
    z = 2.0 / (1.0 - 0.5 * x_per_z)
    scan = convert(np.tile(z, (HEIGHT, 1)), LENS, Settings())
    angles = beam_angles(scan.angle_min, scan.angle_increment)
    # each beam at scan angle a: the ray (x, z) = r(-sin a, cos a) meets z = 2 + 0.5 x
    expected = 2.0 / (np.cos(angles) + 0.5 * np.sin(angles))
    finite = np.isfinite(scan.ranges)
    assert np.allclose(scan.ranges[finite], expected[finite], atol=1e-2)


def test_the_nearest_row_wins_and_limits_drop_readings() -> None:
    depth = wall_depth(4.0)
    middle = int(LENS.cy)
    depth[middle - 2, 100:200] = 1.0  # within a scan_height of 10
    depth[middle + 40, 300:400] = 0.5  # outside it
    depth[:, 500:] = 0.2  # nearer than range_min: dropped
    scan = convert(depth, LENS, Settings(scan_height=10, range_min=0.45, range_max=10.0))
    post = beams_between(column_angle(190), column_angle(110))
    assert np.nanmax(scan.ranges[post]) < 1.1 and np.nanmin(scan.ranges[post]) >= 1.0
    below = beams_between(column_angle(390), column_angle(310))
    assert np.nanmin(scan.ranges[below]) > 3.9
    assert np.isnan(scan.ranges[beams_between(-1.0, column_angle(505))]).all()
    scan = convert(depth, LENS, Settings(scan_height=10, range_max=3.0))
    assert np.isnan(scan.ranges[below]).all()


def test_nan_and_inf_follow_upstream() -> None:
    depth = np.full((HEIGHT, WIDTH), np.nan)
    depth[:, 10:20] = np.inf
    depth[int(LENS.cy), 15] = 2.0
    scan = convert(depth, LENS, Settings(scan_height=5))
    infinite = beams_between(column_angle(18), column_angle(11))
    assert np.isinf(scan.ranges[infinite]).any() and np.isnan(scan.ranges[300])
    assert np.isfinite(scan.ranges).sum() == 1  # a finite reading beats an infinity
    assert not np.isnan(scan.ranges[infinite]).any()


def test_16uc1_in_millimetres_and_its_zero() -> None:
    pixels = np.full((4, 3), 1500, dtype="<u2")
    pixels[0, 0] = 0
    depth = depth_in_meters(pixels.tobytes(), 3, 4, 6, "16UC1")
    assert depth[1, 1] == pytest.approx(1.5) and np.isnan(depth[0, 0])
    floats = np.full((2, 2), 2.5, dtype="<f4")
    padded = np.zeros((2, 12), dtype=np.uint8)
    padded[:, :8] = floats.view(np.uint8)
    assert depth_in_meters(padded.tobytes(), 2, 2, 12, "32FC1").tolist() == [[2.5, 2.5], [2.5, 2.5]]


def test_refusals_say_why() -> None:
    with pytest.raises(ConversionError, match="unsupported encoding: rgb8"):
        depth_in_meters(b"\0" * 12, 2, 2, 6, "rgb8")
    with pytest.raises(ConversionError, match=r"scan_height \( 500 pixels\) is too large"):
        convert(wall_depth(1.0), LENS, Settings(scan_height=500))
    with pytest.raises(ConversionError, match="not calibrated"):
        Projection.from_p([0.0] * 12)
    with pytest.raises(ConversionError, match="needs"):
        depth_in_meters(b"\0" * 10, 2, 2, 8, "32FC1")
