"""image_proc: rectification of a distorted chessboard gives straight rows (within a pixel);
debayer, crop_decimate and resize; and live: a video of chessboard views through usb_cam (with
the camera's known calibration), image_proc's image_rect checked by cameracheck.py, the
rectify's interpolation changed by dynparam, and nodelet's standalone resize."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from kame.camera.calibration_files import Calibration, dump
from kame.camera.calibrator import find_chessboard, linear_error
from kame.camera.image_processing import CropDecimate, RectifyMaps, Resize, debayer
from sensor_msgs.msg import CameraInfo
from tests.support import Proc
from tests.turtlesim.sim import BIN, Sim, master, wait_until

cv2 = pytest.importorskip("cv2")
from tests.camera.synthetic import BOARD, HEIGHT, WIDTH, D, K, Renderer, poses  # noqa: E402 - needs OpenCV

PROBE = Path(__file__).with_name("probe.py")


def known_camera() -> CameraInfo:
    projection = np.zeros((3, 4))
    projection[:, :3] = K
    return CameraInfo(width=WIDTH, height=HEIGHT, distortion_model="plumb_bob", K=K.ravel().tolist(),
                      D=D.tolist(), R=np.eye(3).ravel().tolist(), P=projection.ravel().tolist())


@pytest.fixture(scope="module")
def views() -> list[np.ndarray]:
    renderer = Renderer()
    return [renderer.view(*pose) for pose in poses()]


def test_rectified_rows_are_straight(views: list[np.ndarray]) -> None:
    maps = RectifyMaps()
    worst_before = worst_after = 0.0
    for view in views:
        corners = find_chessboard(cv2, view, BOARD)
        rectified = find_chessboard(cv2, maps.rectify(view, known_camera()), BOARD)
        assert corners is not None and rectified is not None
        worst_before = max(worst_before, linear_error(corners, BOARD))
        worst_after = max(worst_after, linear_error(rectified, BOARD))
    assert worst_before > 1.0  # the lens bends rows near the edges by more than a pixel
    assert worst_after < 0.5  # rectified, every row of every view is straight within half a pixel


def test_debayer_crop_decimate_and_resize() -> None:
    bgr = np.zeros((40, 60, 3), np.uint8)
    bgr[:, :, 2] = 200  # red
    bayer = np.zeros((40, 60), np.uint8)
    bayer[0::2, 0::2] = bgr[0::2, 0::2, 2]  # RGGB: red at even rows and columns
    bayer[0::2, 1::2] = bgr[0::2, 1::2, 1]
    bayer[1::2, 0::2] = bgr[1::2, 0::2, 1]
    bayer[1::2, 1::2] = bgr[1::2, 1::2, 0]
    for algorithm in range(4):
        assert np.abs(debayer(bayer, "bayer_rggb8", algorithm)[5:-5, 5:-5].astype(int) - bgr[5:-5, 5:-5]).max() <= 2
    picture = np.arange(40 * 60, dtype=np.uint16).reshape(40, 60)
    out, info = CropDecimate(decimation_x=2, decimation_y=2, x_offset=10, y_offset=4, width=20, height=16).apply(
        picture, known_camera())
    assert out.shape == (8, 10) and out[0, 0] == picture[4, 10] and out[1, 1] == picture[6, 12]
    assert (info.binning_x, info.binning_y, info.roi.x_offset, info.roi.y_offset, info.roi.width, info.roi.height,
            info.roi.do_rectify) == (2, 2, 10, 4, 20, 16, True)
    small, scaled = Resize(scale_width=0.5, scale_height=0.25).apply(np.zeros((480, 640, 3), np.uint8),
                                                                     known_camera())
    assert small.shape == (120, 320, 3) and scaled is not None
    assert (scaled.width, scaled.height, scaled.K[0], scaled.K[4], scaled.P[2]) == pytest.approx(
        (320, 120, K[0, 0] / 2, K[1, 1] / 4, K[0, 2] / 2))


def chessboard_camera(sim: Sim, views: list[np.ndarray], tmp_path: Path) -> None:
    """usb_cam playing a video of the views, with the known calibration."""
    video = tmp_path / "views.avi"
    writer = cv2.VideoWriter(str(video), cv2.VideoWriter_fourcc(*"MJPG"), 10, (WIDTH, HEIGHT))
    for view in views[:8]:
        writer.write(cv2.cvtColor(view, cv2.COLOR_GRAY2BGR))
    writer.release()
    calibration = tmp_path / "lens.yaml"
    calibration.write_text(dump(Calibration("lens", known_camera()), "yaml"))
    sim.start("usb_cam", "usb_cam_node", f"_video_device:={video}", "_pixel_format:=yuyv", "_framerate:=10",
              "_camera_name:=lens", f"_camera_info_url:=file://{calibration}")


def test_image_proc_rectifies_and_cameracheck_agrees(views: list[np.ndarray], tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        chessboard_camera(sim, views, tmp_path)
        sim.start("image_proc", "image_proc", env={**sim.env, "ROS_NAMESPACE": "usb_cam"})
        check = sim.start("camera_calibration", "cameracheck.py", "--size", "8x6", "--square", "0.108",
                          "monocular:=/usb_cam")
        line = check.wait_line("Linearity RMS Error", timeout=60)
        linearity, reprojection = float(line.split()[3]), float(line.split()[8])
        assert linearity < 1.0 and reprojection < 1.5, line  # straight within a pixel, through yuyv and mjpeg
        colour = json.loads(sim.run(sys.executable, str(PROBE), "images", "/usb_cam/image_rect_color", "1",
                                    str(tmp_path / "rect.npz")).stdout.splitlines()[-1])
        assert (colour["encoding"], colour["width"], colour["height"]) == ("rgb8", WIDTH, HEIGHT)
        sim.run("rosrun", "dynamic_reconfigure", "dynparam", "set", "/usb_cam/image_proc_rectify_mono",
                "interpolation", "0")
        assert sim.run("rosparam", "get", "/usb_cam/image_proc_rectify_mono/interpolation").stdout.strip() == "0"


def test_nodelet_standalone_resize(views: list[np.ndarray], tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        chessboard_camera(sim, views, tmp_path)
        sim.start("nodelet", "nodelet", "standalone", "image_proc/resize", "__name:=half", "image:=/usb_cam/image_raw",
                  "camera_info:=/usb_cam/camera_info", "_scale_width:=0.5", "_scale_height:=0.5")
        fields = json.loads(sim.run(sys.executable, str(PROBE), "images", "/half/image", "1",
                                    str(tmp_path / "half.npz")).stdout.splitlines()[-1])
        assert (fields["width"], fields["height"]) == (WIDTH // 2, HEIGHT // 2)
        info = json.loads(sim.run(sys.executable, str(PROBE), "info", "/half/camera_info").stdout)
        assert info["K"][0] == pytest.approx(K[0, 0] / 2)


def test_image_procs_launch_file_with_a_nodelet_manager(views: list[np.ndarray], tmp_path: Path) -> None:
    launch = tmp_path / "camera.launch"
    launch.write_text("""<launch>
  <node pkg="nodelet" type="nodelet" name="manager" args="manager" />
  <group ns="usb_cam">
    <include file="$(find image_proc)/launch/image_proc.launch">
      <arg name="manager" value="/manager" />
    </include>
  </group>
</launch>
""")
    with master(tmp_path) as sim:
        chessboard_camera(sim, views, tmp_path)
        roslaunch = Proc([str(BIN / "roslaunch"), str(launch)], sim.env, cwd=sim.home)
        sim.procs.append(roslaunch)
        colour = json.loads(sim.run(sys.executable, str(PROBE), "images", "/usb_cam/image_rect_color", "1",
                                    str(tmp_path / "rect.npz")).stdout.splitlines()[-1])
        assert (colour["encoding"], colour["width"]) == ("rgb8", WIDTH)
        mono = json.loads(sim.run(sys.executable, str(PROBE), "images", "/usb_cam/image_rect", "1",
                                  str(tmp_path / "mono.npz")).stdout.splitlines()[-1])
        assert mono["encoding"] == "mono8"
        assert "interpolation" in sim.run("rosparam", "list", "/usb_cam/rectify_color").stdout


def test_image_proc_listens_to_the_camera_only_while_someone_listens_to_it(tmp_path: Path) -> None:
    def subscribers() -> str:
        return sim.run("rostopic", "info", "/usb_cam/image_raw").stdout.split("Subscribers:")[1]

    with master(tmp_path) as sim:
        sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_framerate:=10", "_image_width:=160",
                  "_image_height:=120")
        sim.start("image_proc", "image_proc", env={**sim.env, "ROS_NAMESPACE": "usb_cam"})
        wait_until(lambda: "/usb_cam/image_proc" in sim.run("rosnode", "list").stdout, timeout=30,
                   what="image_proc to register")
        assert "/usb_cam/image_proc" not in subscribers()
        fields = json.loads(sim.run(sys.executable, str(PROBE), "images", "/usb_cam/image_color", "2",
                                    str(tmp_path / "colour.npz")).stdout.splitlines()[-1])
        assert (fields["encoding"], fields["width"]) == ("rgb8", 160)  # colour passes through debayer
        wait_until(lambda: "/usb_cam/image_proc" not in subscribers(), timeout=30,
                   what="image_proc to let the camera go once its listener left")
