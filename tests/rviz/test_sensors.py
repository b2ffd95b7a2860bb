"""rviz's sensor displays: Range's cone, WrenchStamped's arrows, Image's pixels, and Camera's
projection through CameraInfo; then the Image and Camera panels of the window (offscreen: they
paint with QPainter, not OpenGL) show the image and, for Camera, the 3-D scene over it."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from geometry_msgs.msg import PointStamped, WrenchStamped
from kame.rviz import config, sensors
from kame.rviz.display import ERROR, OK, WARN
from kame.rviz.scene import Scene
from sensor_msgs.msg import CameraInfo, Image, Range
from tests.rviz.test_model import TREE, TreeOf, all_vertices, build


def _range(distance: float, low: float = 0.1, high: float = 4.0) -> Range:
    message = Range(field_of_view=math.radians(60), min_range=low, max_range=high, range=distance)
    message.header.frame_id = "laser"
    return message


def test_range_draws_a_cone_along_the_sensor_x_as_long_as_the_range() -> None:
    display = sensors.Range()
    vertices = all_vertices(build(display, _range(2.0)))
    assert display.status.level == OK
    # laser is at (1, 2, 0); the cone reaches x = 3 and is 2 tan 30 deg wide either side
    assert vertices.min(axis=0) == pytest.approx([1, 2 - 2 * math.tan(math.radians(30)), -2 * math.tan(
        math.radians(30))], abs=1e-3)
    assert vertices.max(axis=0)[0] == pytest.approx(3.0)
    assert not build(display, _range(5.0)).batches  # beyond max_range: nothing
    fixed = _range(-math.inf, 0.5, 0.5)  # a fixed-distance ranger's "something is there"
    assert all_vertices(build(display, fixed)).max(axis=0)[0] == pytest.approx(1.5)


def test_wrench_draws_force_and_torque_arrows_scaled() -> None:
    display = sensors.WrenchStamped()
    wrench = WrenchStamped()
    wrench.header.frame_id = "odom"
    wrench.wrench.force.x = 1.5
    wrench.wrench.torque.z = 0.5
    scene = build(display, wrench)
    assert display.status.level == OK
    triangles = next(b for b in scene.batches if b.kind == "triangles")
    force = triangles.vertices[np.all(np.isclose(triangles.colors[:, :3], (0.8, 0.2, 0.2), atol=0.01), axis=1)]
    torque = triangles.vertices[np.all(np.isclose(triangles.colors[:, :3], (0.8, 0.8, 0.2), atol=0.01), axis=1)]
    assert force.max(axis=0)[0] == pytest.approx(1 + 1.5 * 2)  # odom at x = 1, Force Arrow Scale 2
    assert torque.max(axis=0)[2] == pytest.approx(0.5 * 2)
    assert [b.kind for b in scene.batches] == ["triangles", "lines"]  # the torque's circle
    wrench.wrench.force.y = math.nan
    build(display, wrench)
    assert display.status.level == WARN and "NaN" in display.status.text


def _image(encoding: str, width: int, height: int, pixel: bytes, frame: str = "cam") -> Image:
    image = Image(encoding=encoding, width=width, height=height, step=width * len(pixel), data=pixel * width * height)
    image.header.frame_id = frame
    return image


def test_image_decodes_the_common_encodings_to_rgba() -> None:
    display = sensors.Image()
    assert display.topic == "/image" and display.side_topics() == {}
    build(display, _image("bgr8", 2, 1, bytes([255, 0, 0])))
    assert display.status.level == OK and display.pixels is not None
    assert display.pixels.shape == (1, 2, 4) and display.pixels[0, 0].tolist() == [0, 0, 255, 255]
    build(display, _image("mono8", 3, 2, bytes([7])))
    assert display.pixels is not None and display.pixels[1, 2].tolist() == [7, 7, 7, 255]
    build(display, _image("yuv422", 2, 2, bytes([1, 2])))
    assert display.status.level == ERROR and "yuv422" in display.status.text and display.pixels is None


def _camera_info(frame: str = "cam") -> CameraInfo:
    info = CameraInfo(width=100, height=100, P=[100.0, 0, 50, 0, 0, 100, 50, 0, 0, 0, 1, 0])
    info.header.frame_id = frame
    return info


def test_camera_reads_camera_info_beside_the_image_and_projects_through_it() -> None:
    display = sensors.Camera(options={"Image Topic": "/camera/rgb/image_raw"})
    assert display.side_topics() == {"/camera/rgb/camera_info": "sensor_msgs/CameraInfo"}
    frames = TreeOf("map", {"cam": ("map", (0.0, 0.0, 1.0))})  # looking up the map's z from 1 m
    display.receive([_image("rgb8", 100, 100, bytes([0, 0, 255]))], 0.0)
    display.build(Scene(), frames, 0.0)
    assert display.status.level == WARN and "/camera/rgb/camera_info" in display.status.text
    display.receive_side("/camera/rgb/camera_info", [_camera_info()], 0.0)

    display.build(Scene(), frames, 0.0)
    assert display.status.level == OK
    pixels, in_front = display.project(np.array([[0.0, 0.0, 6.0], [1.0, -0.5, 6.0], [0.0, 0.0, -1.0]]))
    assert pixels[:2].tolist() == [[50.0, 50.0], [70.0, 40.0]]
    assert in_front.tolist() == [True, True, False]


def test_the_sensor_displays_load_from_a_rviz_file() -> None:
    loaded = config.parse("""
Visualization Manager:
  Displays:
    - {Class: rviz/Camera, Name: Camera, Enabled: true, Image Topic: /camera/rgb/image_raw, Overlay Alpha: 0.5}
    - {Class: rviz/Image, Name: Image, Enabled: true, Image Topic: /camera/depth/image_raw}
    - {Class: rviz/Range, Name: Range, Enabled: true, Topic: /sonar}
    - {Class: rviz/WrenchStamped, Name: Wrench, Enabled: true, Topic: /ft}
""")
    assert loaded.unknown_displays == []
    assert [(d.class_name, d.topic) for d in loaded.displays] == [
        ("rviz/Camera", "/camera/rgb/image_raw"), ("rviz/Image", "/camera/depth/image_raw"),
        ("rviz/Range", "/sonar"), ("rviz/WrenchStamped", "/ft")]


def test_the_image_and_camera_panels_show_the_image_and_the_scene_over_it(qtbot: Any) -> None:
    pytest.importorskip("OpenGL", reason="rviz's window needs PyOpenGL (pip install 'kame[gui]')")
    pytest.importorskip("PySide6")
    from kame.rviz.displays import PointStamped as PointDisplay
    from kame.rviz.window import RvizWindow

    camera = sensors.Camera(options={"Image Topic": "/camera/image_raw", "Overlay Alpha": 0.5})
    image = sensors.Image(options={"Image Topic": "/camera/image_raw"})
    point = PointDisplay(options={"Color": "255; 0; 0", "Radius": 0.5})
    settings = config.Config(fixed_frame="map", displays=[camera, image, point])
    window = RvizWindow(settings, None)
    qtbot.addWidget(window)
    window.timer.stop()
    blue = _image("rgb8", 100, 100, bytes([0, 0, 255]))
    camera.receive([blue], 0.0)
    camera.receive_side("/camera/camera_info", [_camera_info()], 0.0)
    image.receive([blue], 0.0)
    clicked = PointStamped()
    clicked.header.frame_id = "map"
    clicked.point.z = 6.0  # 5 m in front of the camera, on its axis
    point.receive([clicked], 0.0)
    window.draw(0.0, TreeOf("map", {"cam": ("map", (0.0, 0.0, 1.0))}))
    assert camera.status.level == OK, camera.status.text
    panels = [window.image_panels.panel(d) for d in (camera, image)]
    assert all(panel is not None for panel in panels)
    camera_panel, image_panel = panels
    assert camera_panel is not None and image_panel is not None
    camera_view = camera_panel.grab().toImage()  # grabbing lays the dock out: then its size is known
    left, top, scale = camera_panel.placement(100, 100)
    centre = round(left + 50 * scale), round(top + 50 * scale)  # the image's pixel (50, 50)
    corner = round(left + 10 * scale), round(top + 10 * scale)
    assert camera_view.pixelColor(*centre).getRgb()[:3] == pytest.approx((128, 0, 128), abs=3)  # red over blue
    assert camera_view.pixelColor(*corner).getRgb()[:3] == (0, 0, 255)
    image_view = image_panel.grab().toImage()
    left, top, scale = image_panel.placement(100, 100)
    assert image_view.pixelColor(round(left + 50 * scale), round(top + 50 * scale)).getRgb()[:3] == (0, 0, 255)
    settings.displays = [point]
    window.draw(0.0, TREE)
    assert window.image_panels.panel(camera) is None  # the display went, and its dock with it


def test_an_image_panels_paint_is_when_its_image_reached_the_screen(qtbot: Any) -> None:
    """KAME_RVIZ_STATS: an image shows in its display's panel, which the 3-D view's swap does not
    follow; each paint of a panel tells the window's shown log."""
    pytest.importorskip("OpenGL", reason="rviz's window needs PyOpenGL (pip install 'kame[gui]')")
    pytest.importorskip("PySide6")
    from kame.rviz.window import RvizWindow

    image = sensors.Image(options={"Image Topic": "/camera/image_raw"})
    window = RvizWindow(config.Config(fixed_frame="map", displays=[image]), None)
    qtbot.addWidget(window)
    window.timer.stop()
    painted: list[bool] = []
    window.image_panels.painted = lambda: painted.append(True)
    image.receive([_image("rgb8", 10, 10, bytes([0, 0, 255]))], 0.0)
    window.draw(0.0, TREE)
    panel = window.image_panels.panel(image)
    assert panel is not None
    panel.grab()
    assert painted


def test_a_compressed_image_is_read_beside_the_topic_and_decoded_by_the_window(qtbot: Any) -> None:
    pytest.importorskip("PySide6")
    from PySide6.QtCore import QBuffer, QByteArray, QIODevice
    from PySide6.QtGui import QColor, QImage

    from kame.rviz.image_panels import decode_compressed
    from sensor_msgs.msg import CompressedImage

    display = sensors.Camera(options={"Image Topic": "/camera/image_raw", "Transport Hint": "compressed"})
    assert display.subscription() == ("/camera/image_raw/compressed", "sensor_msgs/CompressedImage")
    assert display.side_topics() == {"/camera/camera_info": "sensor_msgs/CameraInfo"}
    assert sensors.Image(options={"Image Topic": "/i"}).subscription() == ("/i", "sensor_msgs/Image")
    picture = QImage(4, 3, QImage.Format.Format_RGB888)
    picture.fill(QColor(0, 128, 255))
    encoded = QByteArray()
    sink = QBuffer(encoded)
    sink.open(QIODevice.OpenModeFlag.WriteOnly)
    assert picture.save(sink, "PNG")
    message = CompressedImage(format="png", data=bytes(encoded.data()))
    build(display, message)
    assert display.status.level == ERROR and "decoded by the window" in display.status.text
    display.decode_compressed = decode_compressed
    display.version += 1
    build(display)
    assert display.pixels is not None and display.pixels.shape == (3, 4, 4)
    assert display.pixels[2, 3].tolist() == [0, 128, 255, 255]
    build(display, CompressedImage(format="jpeg", data=b"not a jpeg"))
    assert display.status.level == ERROR and "cannot decode the jpeg image" in display.status.text
