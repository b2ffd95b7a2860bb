"""A flood never stalls rviz's window: `rviz --stats` in its own process on a private Xvfb, fed
a 1 MB PointCloud2 and a 1,000-marker MarkerArray, both at 30 Hz for 4 s, keeps drawing
frames every second with no turn of its event loop held up over 1 s (software GL, a loaded
2-core machine), and then shows the newest cloud and array: both sent once more in colours the
flood never had, read off the screen."""

from __future__ import annotations

import re
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from geometry_msgs.msg import Point, Pose, Quaternion, TransformStamped, Vector3
from kame.node.node import Node, NodeConfig
from kame.node.topics import serialize_frame
from kame.tf_ros.node_io import StaticTransformBroadcaster
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import ColorRGBA
from tests.support import Proc
from tests.tf.graph import Graph
from tests.turtlesim.sim import BIN
from visualization_msgs.msg import Marker, MarkerArray

pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

RVIZ_FILE = """\
Visualization Manager:
  Displays:
    - Class: rviz/PointCloud2
      Enabled: true
      Name: Cloud
      Topic: /cloud
      Style: Points
      Size (Pixels): 2
      Color Transformer: RGB8
    - Class: rviz/MarkerArray
      Enabled: true
      Name: Markers
      Marker Topic: /markers
  Global Options:
    Background Color: 48; 48; 48
    Fixed Frame: map
    Frame Rate: 30
  Views:
    Current:
      Class: rviz/TopDownOrtho
      Scale: 50
      X: 0
      Y: 0
Window Geometry:
  Width: 1000
  Height: 600
"""

SIDE = 256  # 65,536 points of 16 bytes: 1 MiB
FLOOD_SECONDS, RATE = 4.0, 30.0  # a cloud and a marker array each tick
ORANGE, CYAN = (255, 128, 0), (0, 255, 255)  # the flood's cloud, the last one
GREEN, MAGENTA = (0, 255, 0), (255, 0, 255)  # the flood's cubes, the last ones
STATS = re.compile(r"rviz stats: ([\d.]+) frames/s drawn, ([\d.]+) turns/s, longest gap (\d+) ms")


def _cloud(rgb: tuple[int, int, int]) -> list[memoryview]:
    """A square of points from (-4, -1.5) to (-1, 1.5) in one colour, serialized."""
    points = np.zeros(SIDE * SIDE, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("rgb", "<u4")])
    points["x"] = np.repeat(np.linspace(-4.0, -1.0, SIDE), SIDE)
    points["y"] = np.tile(np.linspace(-1.5, 1.5, SIDE), SIDE)
    points["rgb"] = (rgb[0] << 16) | (rgb[1] << 8) | rgb[2]
    fields = [PointField(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate(("x", "y", "z", "rgb"))]
    cloud = PointCloud2(height=1, width=SIDE * SIDE, fields=fields, point_step=16, row_step=16 * SIDE * SIDE,
                        data=points.tobytes(), is_dense=True)
    cloud.header.frame_id = "map"
    return list(serialize_frame(cloud))


def _cubes(rgb: tuple[int, int, int]) -> list[memoryview]:
    """1,000 cubes, 40 by 25, from (1, -1.5) to (4, 1.5), serialized (the same ids each time)."""
    colour = ColorRGBA(*(c / 255 for c in rgb), 1.0)
    array = MarkerArray()
    for i in range(1000):
        marker = Marker(ns="flood", id=i, type=Marker.CUBE, color=colour, scale=Vector3(0.06, 0.06, 0.06),
                        pose=Pose(position=Point(1.0 + (i % 40) * 3 / 39, -1.5 + (i // 40) * 3 / 24, 0.0),
                                  orientation=Quaternion(0, 0, 0, 1)))
        marker.header.frame_id = "map"
        array.markers.append(marker)
    return list(serialize_frame(array))


def _rgb(shot: Any) -> np.ndarray:
    raw = np.frombuffer(shot.data[:shot.height * shot.bytes_per_line], dtype=np.uint8)
    rows = raw.reshape(shot.height, shot.bytes_per_line)[:, :shot.width * shot.bytes_per_pixel]
    pixel = rows.reshape(shot.height, shot.width, shot.bytes_per_pixel)
    return (pixel[:, :, 2::-1][:, :, :3] if shot.little_endian else pixel[:, :, -3:]).astype(np.int32)


def _count(image: np.ndarray, colour: tuple[int, int, int]) -> int:
    """Pixels of `colour` as the headlight may shade it (a cube's top faces the camera: its own)."""
    wanted = np.asarray(colour)
    return int((np.abs(image - wanted).sum(axis=2) <= 30).sum())


def _reports(rviz: Proc) -> list[tuple[float, float, int]]:
    found = (STATS.search(line) for line in list(rviz.out))
    return [(float(m.group(1)), float(m.group(2)), int(m.group(3))) for m in found if m]


def test_a_cloud_and_a_marker_array_at_30_hz_never_stall_the_window(tmp_path: Path) -> None:
    from tests.turtlesim.xserver import find_window, screenshot, xvfb

    graph = Graph(tmp_path)
    talker = Node(NodeConfig("/flood", graph.uri, "127.0.0.1", "127.0.0.1"))
    try:
        rviz_file = tmp_path / "flood.rviz"
        rviz_file.write_text(RVIZ_FILE)
        tf = TransformStamped()  # rviz draws nothing in a fixed frame tf does not know
        tf.header.frame_id, tf.child_frame_id = "map", "odom"
        tf.transform.rotation.w = 1.0
        StaticTransformBroadcaster(talker).send_transform(tf)
        connected = {"/cloud": threading.Event(), "/markers": threading.Event()}
        clouds = talker.advertise("/cloud", PointCloud2._type, PointCloud2._md5sum, PointCloud2._full_text,
                                  on_connect=lambda link: connected["/cloud"].set())
        arrays = talker.advertise("/markers", MarkerArray._type, MarkerArray._md5sum, MarkerArray._full_text,
                                  on_connect=lambda link: connected["/markers"].set())
        flood_cloud, last_cloud, flood_cubes, last_cubes = _cloud(ORANGE), _cloud(CYAN), _cubes(GREEN), _cubes(MAGENTA)
        with xvfb("1280x800") as display:
            env = {k: v for k, v in graph.env.items() if k not in ("WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
            rviz = Proc([str(BIN / "rviz"), "--stats", "-d", str(rviz_file)], dict(env, DISPLAY=display))
            graph.procs.append(rviz)
            assert all(event.wait(60) for event in connected.values()), "".join(rviz.err)
            rviz.wait_line("rviz stats:", timeout=60)
            before = len(_reports(rviz))
            start = time.monotonic()
            sent = 0
            while time.monotonic() - start < FLOOD_SECONDS:
                clouds.publish_frame(flood_cloud)
                arrays.publish_frame(flood_cubes)
                sent += 1
                time.sleep(max(0.0, start + sent / RATE - time.monotonic()))  # paced at 30 Hz
            clouds.publish_frame(last_cloud)
            arrays.publish_frame(last_cubes)
            flooded = _reports(rviz)[before:]  # each second of the flood (the last may be cut short)
            assert len(flooded) >= FLOOD_SECONDS - 1, (flooded, "".join(rviz.err)[-2000:])
            assert all(drawn >= 1 and gap <= 1000 for drawn, _, gap in flooded), flooded
            assert sum(drawn for drawn, _, _ in flooded) >= 10, flooded  # new clouds mean new frames

            window = None
            deadline = time.monotonic() + 60
            while window is None and time.monotonic() < deadline:
                window = find_window(display, "flood.rviz - RViz")
                time.sleep(0.1)
            assert window is not None
            counts: dict[tuple[int, int, int], int] = {}
            deadline = time.monotonic() + 15  # the newest of both is shown soon after the flood ends
            while time.monotonic() < deadline:
                image = _rgb(screenshot(display, window.id))
                counts = {colour: _count(image, colour) for colour in (ORANGE, CYAN, GREEN, MAGENTA)}
                if counts[CYAN] > 5000 and counts[MAGENTA] > 1000 and not counts[ORANGE] and not counts[GREEN]:
                    break
                time.sleep(0.2)
            # the cloud's 150 x 150 pixels, the cubes' 1,000 of 3 x 3
            assert counts[CYAN] > 5000 and counts[MAGENTA] > 1000, counts
            assert counts[ORANGE] == 0 and counts[GREEN] == 0, counts
            assert rviz.popen.poll() is None, "".join(rviz.err)
    finally:
        talker.shutdown("test over")
        graph.stop()
