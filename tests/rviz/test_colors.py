"""rviz's colour transformers for clouds and scans, without a window: Intensity (rainbow and
min/max colours, own or given bounds), AxisColor (fixed frame or the cloud's), RGB8, RGBF32,
MONO8, FlatColor, rviz's choice when none is named, and Decay Time keeping older messages."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from kame.rviz import displays
from kame.rviz.colors import rainbow
from sensor_msgs.msg import LaserScan, PointCloud2, PointField
from tests.rviz.test_model import all_vertices, build

RED, MAGENTA, MID = [255, 0, 0, 255], [255, 0, 255, 255], [0, 255, 128, 255]


def cloud_of(**columns: Any) -> PointCloud2:
    """A cloud in odom (the test tree's: 1 m along the map's x) of float32 fields x, y, z, ..."""
    names = list(columns)
    points = np.zeros(len(columns["x"]), dtype=[(n, "<f4") for n in names])
    for name, values in columns.items():
        points[name] = values
    fields = [PointField(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate(names)]
    cloud = PointCloud2(height=1, width=len(points), fields=fields, point_step=4 * len(names),
                        row_step=4 * len(names) * len(points), data=points.tobytes())
    cloud.header.frame_id = "odom"
    return cloud


def colors(display: displays.PointCloudCommon, message: Any) -> list[list[int]]:
    batch = build(display, message).batches[0]
    assert not batch.uniform
    return [list(map(int, c)) for c in batch.colors]


def test_rainbow_runs_from_red_to_magenta_as_rvizs() -> None:
    assert (rainbow(np.array([1.0, 0.5, 0.0, 2.0, -1.0])) * 255).round().tolist() == [
        [255, 0, 0], [0, 255, 128], [255, 0, 255], [255, 0, 0], [255, 0, 255]]


def test_a_cloud_with_intensity_is_a_rainbow_by_default_lowest_red() -> None:
    cloud = cloud_of(x=[0, 1, 2], y=[0, 0, 0], z=[0, 0, 0], intensity=[10, 60, 110])
    assert colors(displays.PointCloud2(), cloud) == [RED, MID, MAGENTA]
    assert colors(displays.PointCloud2(options={"Invert Rainbow": True}), cloud) == [MAGENTA, MID, RED]
    # given bounds: 110 is past the maximum (clamped to magenta), 10 is a quarter of the way
    bounded = displays.PointCloud2(options={"Autocompute Intensity Bounds": False, "Min Intensity": 0,
                                            "Max Intensity": 40, "Alpha": 0.5})
    got = colors(bounded, cloud)
    assert got[2] == [255, 0, 255, 128] and got[0] == [191, 255, 0, 128]  # rainbow(0.75)


def test_intensity_between_min_and_max_colour_without_the_rainbow() -> None:
    cloud = cloud_of(x=[0, 1, 2], y=[0, 0, 0], z=[0, 0, 0], strength=[0, 5, 10])
    display = displays.PointCloud2(options={"Color Transformer": "Intensity", "Channel Name": "strength",
                                            "Use rainbow": False, "Min Color": "0; 0; 255", "Max Color": "255; 0; 0"})
    assert colors(display, cloud) == [[0, 0, 255, 255], [128, 0, 128, 255], [255, 0, 0, 255]]


def test_a_missing_channel_draws_the_flat_colour() -> None:
    cloud = cloud_of(x=[0, 1], y=[0, 0], z=[0, 0])
    batch = build(displays.PointCloud2(options={"Color Transformer": "Intensity", "Color": "0; 255; 0"}),
                  cloud).batches[0]
    assert batch.uniform and batch.colors[0] == pytest.approx([0, 1, 0, 1])


def test_axis_colour_in_the_fixed_frame_or_the_clouds_own() -> None:
    cloud = cloud_of(x=[0, 1, 2], y=[0, 0, 0], z=[2, 1, 0])
    assert colors(displays.PointCloud2(options={"Color Transformer": "AxisColor"}), cloud) == [MAGENTA, MID, RED]
    # the cloud's x is 1..3 in the map: with the map's bounds 0..3 the first point is a third up
    bounds = {"Value": False, "Min Value": 0, "Max Value": 3}  # as a .rviz file nests them
    fixed = displays.PointCloud2(options={"Color Transformer": "AxisColor", "Axis": "X",
                                          "Autocompute Value Bounds": bounds})
    own = displays.PointCloud2(options={"Color Transformer": "AxisColor", "Axis": "X", "Use Fixed Frame": False,
                                        "Autocompute Value Bounds": bounds})
    assert colors(fixed, cloud)[2] == MAGENTA and colors(own, cloud)[0] == RED
    assert colors(fixed, cloud)[0] != RED


def test_rgb_fields_and_grey() -> None:
    cloud = cloud_of(x=[0, 1], y=[0, 0], z=[0, 0], r=[1.0, 0.0], g=[0.5, 0.0], b=[0.0, 1.0])
    assert colors(displays.PointCloud2(options={"Color Transformer": "RGBF32"}), cloud) == [
        [255, 128, 0, 255], [0, 0, 255, 255]]
    packed = np.array([0xFF0000, 0x0000FF], dtype="<u4").view("<f4")
    rgb = cloud_of(x=[0, 1], y=[0, 0], z=[0, 0], rgb=packed)
    assert colors(displays.PointCloud2(options={"Color Transformer": "MONO8"}), rgb) == [
        [76, 76, 76, 255], [28, 28, 28, 255]]
    # a FlatColor-less name the cloud cannot give falls back as rviz's: rgb first
    assert colors(displays.PointCloud2(options={"Color Transformer": "RGBF32"}), rgb) == [
        [255, 0, 0, 255], [0, 0, 255, 255]]


def test_rgba_keeps_each_points_alpha() -> None:
    packed = np.array([0x80FF0000, 0xFF00FF00], dtype="<u4").view("<f4")
    cloud = cloud_of(x=[0, 1], y=[0, 0], z=[0, 0], rgba=packed)
    assert colors(displays.PointCloud2(), cloud) == [[255, 0, 0, 128], [0, 255, 0, 255]]


def test_a_scans_intensities_colour_it_and_a_scan_without_is_flat() -> None:
    scan = LaserScan(angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=10.0, ranges=[1.0, 1.0, 50.0],
                     intensities=[100.0, 200.0, 0.0])
    scan.header.frame_id = "laser"
    # the out-of-range third ray is no point, so its intensity does not bound the rainbow (laser_geometry's)
    assert colors(displays.LaserScan(options={"Color Transformer": "Intensity"}), scan) == [RED, MAGENTA]
    scan.intensities = []
    flat = build(displays.LaserScan(options={"Color Transformer": "Intensity"}), scan).batches[0]
    assert flat.uniform and flat.colors[0] == pytest.approx([1, 0, 0, 1])


def test_decay_time_keeps_older_messages_until_they_are_older_than_it() -> None:
    display = displays.PointCloud2(options={"Decay Time": 1.0, "Color Transformer": "FlatColor"})
    build(display, cloud_of(x=[0], y=[0], z=[0]), now=0.0)
    scene = build(display, cloud_of(x=[5], y=[0], z=[0]), now=0.5)
    assert sorted(all_vertices(scene)[:, 0]) == [1.0, 6.0]
    later = build(display, now=1.2)
    assert all_vertices(later)[:, 0].tolist() == [6.0]
    assert build(display, now=1.4).batches[0] is later.batches[0]  # nothing decayed since: not drawn again
    assert build(display, now=1.6).batches == []  # rviz lets the newest decay too
    newest = build(displays.PointCloud2(), cloud_of(x=[0], y=[0], z=[0]), cloud_of(x=[5], y=[0], z=[0]))
    assert all_vertices(newest)[:, 0].tolist() == [6.0]  # no decay: the newest alone


def test_the_points_style_is_pixels_wide_and_the_others_metres() -> None:
    cloud = cloud_of(x=[0], y=[0], z=[0])
    squares = build(displays.PointCloud2(), cloud).batches[0]  # rviz's default: Flat Squares, 0.01 m
    assert squares.metres and squares.size == pytest.approx(0.01)
    boxes = build(displays.PointCloud2(options={"Style": "Boxes", "Size (m)": 0.2}), cloud).batches[0]
    assert boxes.metres and boxes.size == pytest.approx(0.2)
    points = build(displays.PointCloud2(options={"Style": "Points", "Size (Pixels)": 5}), cloud).batches[0]
    assert not points.metres and points.size == 5
