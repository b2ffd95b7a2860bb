"""rviz's Measure and Select tools without a window: two clicks measure, a rectangle (or a
click) selects the points and markers inside it with rviz's names and properties."""

from __future__ import annotations

import numpy as np
import pytest

from kame.rviz import displays, markers
from kame.rviz.camera import TOP_DOWN, Camera
from kame.rviz.tools import Measure, Selection
from tests.rviz.test_colors import cloud_of
from tests.rviz.test_model import build
from visualization_msgs.msg import Marker

WIDTH, HEIGHT = 900, 500


def test_two_clicks_measure_and_a_third_starts_again() -> None:
    measure = Measure()
    assert measure.status().startswith("[Left-Click] Select start point")
    measure.click(np.array([0.0, 0.0, 0.0]))
    assert measure.length is None and "start: 0; 0; 0" in measure.status()
    assert measure.overlay.batches[0].kind == "points"
    measure.click(np.array([3.0, 4.0, 0.0]))
    assert measure.length == pytest.approx(5.0)
    assert measure.status().endswith("length: 5.000 m")
    line = measure.overlay.batches[0]
    assert line.kind == "lines" and line.vertices.tolist() == [[0, 0, 0], [3, 4, 0]] and line.overlay
    measure.click(np.array([1.0, 1.0, 1.0]))
    assert measure.length is None and measure.start == pytest.approx([1, 1, 1])
    measure.reset()
    assert measure.start is None and not measure.overlay.batches


def pixel(camera: Camera, x: float, y: float) -> tuple[float, float]:
    px, py = camera.project(np.array([[x, y, 0.0]]), WIDTH, HEIGHT)[0]
    return float(px), float(py)


def test_a_rectangle_selects_the_points_inside_with_their_fields() -> None:
    camera = Camera(kind=TOP_DOWN, scale=50.0)
    cloud = displays.PointCloud2()
    # odom is 1 m along the map's x: the points are at map x 1, (none), 3, 5
    build(cloud, cloud_of(x=[0, np.nan, 2, 4], y=[0, 0, 0, 0], z=[0, 0, 0, 0], intensity=[7, 8, 9, 10]))
    selection = Selection()
    selection.select([cloud], camera, WIDTH, HEIGHT, pixel(camera, 0.5, -0.5), pixel(camera, 3.5, 0.5))
    assert [(s.display, s.name) for s in selection.selected] == [("PointCloud2", "Point 0"), ("PointCloud2", "Point 2")]
    assert selection.selected[1].properties == {"Position": "3; 0; 0", "intensity": "9"}
    assert selection.total == 2
    assert selection.overlay.batches[0].vertices.tolist() == [[1, 0, 0], [3, 0, 0]]
    assert selection.overlay.batches[0].overlay  # drawn over what it marks
    selection.select([cloud], camera, WIDTH, HEIGHT, pixel(camera, 0.5, -0.5), pixel(camera, 5.5, 0.5), limit=1)
    assert selection.total == 3 and len(selection.selected) == 1
    selection.select([cloud], camera, WIDTH, HEIGHT, pixel(camera, -3, -3), pixel(camera, -2, -2))
    assert selection.selected == [] and not selection.overlay.batches
    cloud.enabled = False
    selection.select([cloud], camera, WIDTH, HEIGHT, pixel(camera, 0.5, -0.5), pixel(camera, 3.5, 0.5))
    assert selection.selected == []


def test_a_click_selects_a_marker() -> None:
    camera = Camera(kind=TOP_DOWN, scale=50.0)
    display = markers.Marker()
    marker = Marker(ns="boxes", id=4, type=markers.CUBE)
    marker.header.frame_id = "odom"
    marker.pose.position.y = 2.0
    marker.pose.orientation.w = 1.0
    marker.scale.x = marker.scale.y = marker.scale.z = 0.5
    marker.color.b = marker.color.a = 1.0
    build(display, marker)
    selection = Selection()
    at = pixel(camera, 1.0, 2.0)
    selection.select([display], camera, WIDTH, HEIGHT, at, (at[0] + 1, at[1]))
    assert [s.name for s in selection.selected] == ["boxes/4"]
    assert selection.selected[0].properties == {
        "Type": "Cube", "Frame": "odom", "Position": "1; 2; 0", "Orientation": "0; 0; 0; 1",
        "Scale": "0.5; 0.5; 0.5", "Color": "0; 0; 1; 1"}
    far = pixel(camera, 1.3, 2.0)  # 15 pixels away
    selection.select([display], camera, WIDTH, HEIGHT, far, far)
    assert selection.selected == []


def test_a_big_cloud_is_drawn_box_by_box_and_its_points_keep_their_names() -> None:
    from kame.rviz.scene import spatial_order

    rng = np.random.default_rng(3)
    xyz = rng.uniform(-4, 4, (20_000, 3)).astype(np.float32)
    xyz[5] = (np.nan, 0, 0)  # not drawn, and the indices after it still name their points
    cloud = displays.PointCloud2()
    batch = build(cloud, cloud_of(x=xyz[:, 0], y=xyz[:, 1], z=xyz[:, 2], intensity=np.arange(20_000))).batches[0]
    finite = np.delete(xyz, 5, axis=0) + np.array([1, 0, 0])  # odom is 1 m along the map's x
    assert np.sort(batch.vertices, axis=0) == pytest.approx(np.sort(finite, axis=0), abs=1e-5)  # reordered
    assert not np.allclose(batch.vertices, finite)
    low, high = batch.vertices.min(axis=0), batch.vertices.max(axis=0)
    boxes = ((batch.vertices - low) * (39 / (high - low))).astype(int)  # 40 boxes an axis, as spatial_order's
    assert (np.diff(boxes[:, 0]) >= 0).all()  # box rows in order
    camera = Camera(kind=TOP_DOWN, scale=50.0)
    target = xyz[1234] + np.array([1, 0, 0])
    at = pixel(camera, float(target[0]), float(target[1]))
    selection = Selection()
    selection.select([cloud], camera, WIDTH, HEIGHT, (at[0] - 0.5, at[1] - 0.5), (at[0] + 0.5, at[1] + 0.5))
    named = {s.name: s for s in selection.selected}
    assert "Point 1234" in named and named["Point 1234"].properties["intensity"] == "1234"
    assert named["Point 1234"].position == pytest.approx(target)
    assert sorted(spatial_order(np.zeros((3, 3), dtype=np.float32))) == [0, 1, 2]  # one box: all of them
