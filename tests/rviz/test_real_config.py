"""A .rviz file saved by Debian's real rviz 1.14.19 (tests/data/rviz/rviz_1.14_every_display.rviz:
every display kame has, added by class and topic, then saved with Ctrl-S so rviz wrote all of
their properties itself) loads in kame's rviz with every display known, each on the topic and
with the options the file gives; saving it keeps what kame does not use (rviz's window
geometry, the Camera's visibility list), so the file still opens in rviz."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from kame.rviz import config
from kame.rviz.camera import ORBIT

REAL = Path(__file__).resolve().parents[1] / "data" / "rviz" / "rviz_1.14_every_display.rviz"


def test_a_file_saved_by_the_real_rviz_loads_with_every_display_on_its_topic() -> None:
    loaded = config.load(str(REAL))
    assert loaded.unknown_displays == []
    assert loaded.fixed_frame == "odom" and loaded.frame_rate == 30
    assert loaded.background == pytest.approx((48 / 255, 48 / 255, 48 / 255, 1.0))
    topics = {d.name: (d.class_name, d.topic) for d in loaded.displays}
    assert topics == {
        "Grid": ("rviz/Grid", ""), "TF": ("rviz/TF", ""), "Axes": ("rviz/Axes", ""),
        "RobotModel": ("rviz/RobotModel", ""), "LaserScan": ("rviz/LaserScan", "/scan"),
        "PointCloud2": ("rviz/PointCloud2", "/points"),
        "Marker": ("rviz/Marker", "/visualization_marker"),
        "MarkerArray": ("rviz/MarkerArray", "/visualization_marker_array"),
        "Map": ("rviz/Map", "/map"), "Path": ("rviz/Path", "/plan"), "Pose": ("rviz/Pose", "/pose"),
        "PoseArray": ("rviz/PoseArray", "/particlecloud"), "PointStamped": ("rviz/PointStamped", "/clicked_point"),
        "Polygon": ("rviz/Polygon", "/footprint"), "Odometry": ("rviz/Odometry", "/odom"),
        "Range": ("rviz/Range", "/sonar"), "WrenchStamped": ("rviz/WrenchStamped", "/wrench"),
        "Image": ("rviz/Image", "/camera/rgb/image_raw"), "Camera": ("rviz/Camera", "/camera/rgb/image_raw")}
    by_name = {d.name: d for d in loaded.displays}
    assert by_name["Grid"].number("Plane Cell Count", 0) == 10 and by_name["Grid"].number("Alpha", 0) == 0.5
    assert by_name["LaserScan"].options["Color Transformer"] == ""  # rviz had seen no scan to choose one for
    assert by_name["Odometry"].options["Shape"]["Color"] == "255; 25; 0"
    assert by_name["RobotModel"].options["Robot Description"] == "robot_description"
    assert by_name["Camera"].number("Overlay Alpha", 0) == 0.5
    assert by_name["Camera"].side_topics() == {"/camera/rgb/camera_info": "sensor_msgs/CameraInfo"}
    camera = loaded.camera
    assert camera.kind == ORBIT and camera.distance == 10
    assert camera.pitch == pytest.approx(0.785398, abs=1e-6) and camera.yaw == pytest.approx(0.785398, abs=1e-6)


def test_saving_the_real_file_keeps_what_rviz_wrote(tmp_path: Path) -> None:
    loaded = config.load(str(REAL))
    saved = tmp_path / "again.rviz"
    config.save(loaded, str(saved))
    original, written = (yaml.safe_load(path.read_text()) for path in (REAL, saved))
    assert written["Window Geometry"] == original["Window Geometry"]
    displays = {d["Name"]: d for d in written["Visualization Manager"]["Displays"]}
    assert displays == {d["Name"]: d for d in original["Visualization Manager"]["Displays"]}
    again = config.load(str(saved))
    assert [(d.class_name, d.topic) for d in again.displays] == [(d.class_name, d.topic) for d in loaded.displays]


def test_odometry_reads_its_arrow_from_the_shape_rviz_writes_and_from_older_flat_keys() -> None:
    from kame.rviz import displays
    from kame.rviz.scene import Scene
    from nav_msgs.msg import Odometry
    from tests.rviz.test_model import TREE

    odometry = Odometry()
    odometry.header.frame_id = "map"
    odometry.pose.pose.orientation.w = 1.0
    for options, color, length in (({"Shape": {"Color": "0; 0; 255", "Shaft Length": 2}}, (0, 0, 1), 2.0),
                                   ({"Color": "0; 255; 0", "Shaft Length": 0.5}, (0, 1, 0), 0.5)):
        display = displays.Odometry(options=options)
        display.receive([odometry], 0.0)
        scene = Scene()
        display.build(scene, TREE, 0.0)
        batch = scene.batches[0]
        assert batch.colors[0][:3] == pytest.approx(color)
        assert batch.vertices[:, 0].max() == pytest.approx(length)


def test_the_window_is_titled_and_sized_as_the_real_rviz_opens_it() -> None:
    loaded = config.load(str(REAL))
    geometry = loaded.raw["Window Geometry"]
    assert config.window_size(loaded) == (geometry["Width"], geometry["Height"])
    assert config.window_size(config.Config()) == (1280, 720)  # no file: kame's default
    # rviz 1.14 names the file, not its folder, and says "RViz" alone without one
    assert config.window_title(str(REAL)) == "rviz_1.14_every_display.rviz - RViz"
    assert config.window_title("") == "RViz"
