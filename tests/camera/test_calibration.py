"""camera_calibration against a known camera: synthetic chessboard views rendered with a known K
and distortion go through the calibrator; K comes back within 1 %, the distortion within
OpenCV's own uncertainty on the same views; ost.yaml and ost.txt read back with kame's parser
and Debian's; a stereo pair 12 cm apart comes back with its baseline and rectifies onto shared
rows. Live under Xvfb: cameracalibrator.py's window (monocular and stereo) collects the views,
and clicks on CALIBRATE, SAVE and COMMIT calibrate, write /tmp/calibrationdata.tar.gz and store
the calibration in usb_cam."""

from __future__ import annotations

import io
import json
import shutil
import subprocess
import sys
import tarfile
from pathlib import Path

import numpy as np
import pytest

from kame.camera.calibration_display import button_at
from kame.camera.calibration_files import parse
from kame.camera.calibration_report import ost_txt, ost_yaml
from kame.camera.calibrator import Board, MonoCalibrator, Options, linear_error, object_points
from tests.libs.debian import SYSTEM_PYTHON, debian_env, has
from tests.support import REPO, Proc
from tests.support.tour import shoot
from tests.turtlesim.sim import master, wait_until
from tests.turtlesim.xserver import Screenshot, find_shown_window, xvfb

cv2 = pytest.importorskip("cv2")
from kame.camera.stereo_calibrator import StereoCalibrator, epipolar_error, square_size  # noqa: E402
from tests.camera.synthetic import BASELINE, BOARD, D, K, Renderer, poses, stereo_poses  # noqa: E402 - needs OpenCV

PROBE = Path(__file__).with_name("probe.py")
VIEWS_NODE = Path(__file__).with_name("views_node.py")


@pytest.fixture(scope="module")
def views() -> list[np.ndarray]:
    renderer = Renderer()
    return [renderer.view(*pose) for pose in poses()]


def calibrated(views: list[np.ndarray], options: Options | None = None) -> MonoCalibrator:
    calibrator = MonoCalibrator(BOARD, options or Options())
    for view in views:
        calibrator.handle(view)
    calibrator.calibrate()
    return calibrator


def test_the_known_camera_comes_back(views: list[np.ndarray]) -> None:
    calibrator = calibrated(views)
    assert calibrator.goodenough and len(calibrator.views) >= 15
    assert calibrator.calibration is not None
    found = calibrator.calibration.K
    for (row, col) in ((0, 0), (1, 1), (0, 2), (1, 2)):  # fx, fy, cx, cy
        assert found[row, col] == pytest.approx(K[row, col], rel=0.01)
    # OpenCV's own uncertainty of the same estimate on the same corners
    corners = [view_corners for _, view_corners, _ in calibrator.views]
    points = [object_points(BOARD)] * len(corners)
    result = cv2.calibrateCameraExtended(points, corners, (640, 480), np.eye(3), None,
                                         flags=cv2.CALIB_FIX_K3 | cv2.CALIB_FIX_K4 | cv2.CALIB_FIX_K5
                                         | cv2.CALIB_FIX_K6)
    sigma = result[5].ravel()[4:8]  # k1, k2, p1, p2
    error = np.abs(calibrator.calibration.D.ravel()[:4] - D[:4])
    assert (error <= 3 * sigma + 1e-4).all(), (error, sigma)


def test_coverage_and_the_buttons(views: list[np.ndarray]) -> None:
    calibrator = MonoCalibrator(BOARD)
    calibrator.handle(views[0])
    assert not calibrator.goodenough and calibrator.progress()[0][0] == "X"
    assert not calibrator.handle(views[0])[1]  # the same view again adds nothing
    assert button_at(690, 230, 640, goodenough=False, calibrated=False) is None
    assert button_at(690, 230, 640, goodenough=True, calibrated=False) == "CALIBRATE"
    assert button_at(690, 330, 640, goodenough=True, calibrated=False) is None
    assert button_at(690, 430, 640, goodenough=True, calibrated=True) == "COMMIT"


def test_options_change_the_model(views: list[np.ndarray]) -> None:
    fixed = calibrated(views, Options(fix_principal_point=True, zero_tangent_dist=True))
    assert fixed.calibration is not None
    assert fixed.calibration.K[0, 2] == pytest.approx(319.5) and fixed.calibration.K[1, 2] == pytest.approx(239.5)
    assert fixed.calibration.D.ravel()[2:4].tolist() == [0.0, 0.0]
    rational = calibrated(views, Options(k_coefficients=6))
    assert rational.calibration is not None
    assert rational.calibration.D.size == 8 and rational.calibration.distortion_model == "rational_polynomial"


def test_rectified_corners_are_straight(views: list[np.ndarray]) -> None:
    calibrator = calibrated(views)
    found = [corners for view in views if (corners := calibrator.handle(view)[0].corners) is not None]
    bent = max(found, key=lambda corners: linear_error(corners, BOARD))
    assert linear_error(bent, BOARD) > 0.4  # the lens bends the board's rows
    assert linear_error(calibrator.rectified_corners(bent), BOARD) < 0.25  # corner noise: 0.15 px


def test_ost_files_read_back(views: list[np.ndarray], tmp_path: Path) -> None:
    calibrator = calibrated(views)
    assert calibrator.calibration is not None
    yaml_text, ini_text = ost_yaml(calibrator.calibration, "narrow_stereo"), ost_txt(calibrator.calibration, "cam")
    from_yaml, from_ini = parse(yaml_text, "yaml"), parse(ini_text, "ini")
    assert from_yaml.camera_name == "narrow_stereo" and from_ini.camera_name == "cam"
    assert list(from_yaml.info.K) == pytest.approx(calibrator.calibration.K.ravel().tolist(), abs=1e-5)
    assert list(from_ini.info.D) == pytest.approx(calibrator.calibration.D.ravel().tolist(), abs=1e-6)
    if not has("camera_calibration_parsers"):
        pytest.skip("Debian's python3-camera-calibration-parsers")
    (tmp_path / "ost.yaml").write_text(yaml_text)
    (tmp_path / "ost.ini").write_text(ini_text)
    script = ("import json, sys, camera_calibration_parsers as c\n"
              "read = map(c.readCalibration, sys.argv[1:])\n"
              "print(json.dumps([[n, list(i.K), list(i.D), list(i.P)] for n, i in read]))")
    result = subprocess.run([str(SYSTEM_PYTHON), "-c", script, str(tmp_path / "ost.yaml"), str(tmp_path / "ost.ini")],
                            capture_output=True, text=True, env=debian_env(), timeout=60)
    assert result.returncode == 0, result.stderr
    for _, k, d, p in json.loads(result.stdout):
        assert k == pytest.approx(calibrator.calibration.K.ravel().tolist(), abs=1e-5)
        assert d == pytest.approx(calibrator.calibration.D.ravel().tolist(), abs=1e-6)
        assert p == pytest.approx(calibrator.calibration.P.ravel().tolist(), abs=1e-5)
    assert [row[0] for row in json.loads(result.stdout)] == ["narrow_stereo", "cam"]


def click(display: str, title: str, x: int, y: int) -> None:
    window = find_shown_window(display, title)
    assert window is not None
    subprocess.run(["xdotool", "mousemove", "--window", window.id, str(x), str(y), "click", "1"],
                   env={"DISPLAY": display}, check=True, timeout=10)


def bars_green(shot: Screenshot, picture_width: int = 640) -> bool:
    """All four bars green and CALIBRATE usable (its button teal, not grey, above its label)."""
    return shot.rgb(picture_width + 50, 200)[2] < 200 and sum(1 for y in (50, 90, 130, 170) if any(
        shot.rgb(x, y) == (0, 255, 0) for x in range(picture_width, picture_width + 100, 2))) == 4


@pytest.mark.skipif(shutil.which("xdotool") is None, reason="xdotool clicks the window's buttons")
def test_calibrate_save_and_commit_in_the_window(tmp_path: Path) -> None:
    tarball = tmp_path / "calibrationdata.tar.gz"  # the calibrator's TMPDIR: /tmp/... for a user
    with xvfb("1024x768") as display, master(tmp_path) as sim:
        sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_framerate:=5")
        views = Proc([sys.executable, str(VIEWS_NODE)], {**sim.env, "PYTHONPATH": str(REPO)}, cwd=sim.home)
        sim.procs.append(views)
        views.wait_line("publishing", timeout=60)
        env = {**sim.env, "DISPLAY": display, "QT_QPA_PLATFORM": "xcb", "TMPDIR": str(tmp_path)}
        calibrator = sim.start("camera_calibration", "cameracalibrator.py", "--size", "8x6", "--square", "0.108",
                               "image:=/camera/image_raw", "camera:=/usb_cam", env=env)
        calibrator.wait_line("OK")  # usb_cam's set_camera_info was found
        shoot(display, "display", "camera_calibration_collecting", bars_green, program=calibrator)
        tarball.unlink(missing_ok=True)
        click(display, "display", 690, 230)
        calibrator.wait_line("**** Calibrating ****")
        calibrator.wait_line("P = ", timeout=60)
        shoot(display, "display", "camera_calibration_calibrated", lambda shot: shot.rgb(690, 300)[2] < 200)
        click(display, "display", 690, 330)
        calibrator.wait_line("Wrote calibration data to")
        with tarfile.open(tarball) as archive:
            names = archive.getnames()
            ost = archive.extractfile("ost.yaml")
            assert ost is not None
            saved = parse(io.TextIOWrapper(ost).read(), "yaml")
        assert {"ost.yaml", "ost.txt", "left-0000.png"} <= set(names)
        assert saved.info.K[0] == pytest.approx(K[0, 0], rel=0.01)
        click(display, "display", 690, 430)
        calibrator.popen.wait(30)  # COMMIT quits once the camera took it
        assert "success: True" in "".join(calibrator.out)
        stored = parse((tmp_path / "camera_info" / "head_camera.yaml").read_text(), "yaml")
        assert list(stored.info.K) == pytest.approx(list(saved.info.K), abs=1e-4)
        info = json.loads(sim.run(sys.executable, str(PROBE), "info", "/usb_cam/camera_info").stdout)
        wait_until(lambda: json.loads(sim.run(sys.executable, str(PROBE), "info", "/usb_cam/camera_info").stdout)
                   ["K"][0] == pytest.approx(K[0, 0], rel=0.01), what="usb_cam to publish the calibration")
        assert info["width"] == 640


def test_a_board_needs_a_size() -> None:
    with pytest.raises(ValueError, match="COLSxROWS"):
        Board.parse("8", 0.1)


def test_a_stereo_pair_comes_back() -> None:
    renderer = Renderer()
    pair = StereoCalibrator(BOARD)
    for rvec, tvec in stereo_poses():
        pair.handle(renderer.view(rvec, tvec), renderer.view(rvec, (tvec[0] - BASELINE, tvec[1], tvec[2])))
    assert pair.goodenough
    calibration = pair.calibrate()
    for side in (calibration.left, calibration.right):
        assert side.K[0, 0] == pytest.approx(K[0, 0], rel=0.01) and side.K[1, 2] == pytest.approx(K[1, 2], rel=0.01)
    assert calibration.translation.ravel()[0] == pytest.approx(-BASELINE, rel=0.02)  # the right camera 12 cm along x
    rvec, tvec = stereo_poses()[3]
    left, right, _ = pair.handle(renderer.view(rvec, tvec), renderer.view(rvec, (tvec[0] - BASELINE, tvec[1], tvec[2])))
    assert left is not None and right is not None
    left, right = pair.rectified_corners(left, right)
    assert epipolar_error(left, right) < 0.5  # rectified, a corner is on the same row in both
    assert square_size(cv2, calibration, left, right, BOARD) == pytest.approx(BOARD.square, rel=0.02)


@pytest.mark.skipif(shutil.which("xdotool") is None, reason="xdotool clicks the window's buttons")
def test_stereo_calibrate_save_and_commit_in_the_window(tmp_path: Path) -> None:
    tarball = tmp_path / "calibrationdata.tar.gz"  # the calibrator's TMPDIR: /tmp/... for a user
    with xvfb("1600x900") as display, master(tmp_path) as sim:
        for side in ("left", "right"):
            sim.start("usb_cam", "usb_cam_node", f"__name:={side}", "_video_device:=testsrc", "_framerate:=5",
                      f"_camera_name:={side}")
        views = Proc([sys.executable, str(VIEWS_NODE), "stereo"], {**sim.env, "PYTHONPATH": str(REPO)}, cwd=sim.home)
        sim.procs.append(views)
        views.wait_line("publishing", timeout=60)
        env = {**sim.env, "DISPLAY": display, "QT_QPA_PLATFORM": "xcb", "TMPDIR": str(tmp_path)}
        calibrator = sim.start("camera_calibration", "cameracalibrator.py", "--size", "8x6", "--square", "0.108",
                               "left:=/stereo/left/image_raw", "right:=/stereo/right/image_raw",
                               "left_camera:=/left", "right_camera:=/right", env=env)
        calibrator.wait_line("OK")
        shoot(display, "display", "camera_calibration_stereo", lambda shot: bars_green(shot, 1280))
        tarball.unlink(missing_ok=True)
        click(display, "display", 1330, 230)
        calibrator.wait_line("self.R =", timeout=60)
        shoot(display, "display", "camera_calibration_stereo_calibrated", lambda shot: shot.rgb(1330, 300)[2] < 200)
        click(display, "display", 1330, 330)
        calibrator.wait_line("Wrote calibration data to")
        with tarfile.open(tarball) as archive:
            names = set(archive.getnames())
        assert {"left.yaml", "right.yaml", "ost.txt", "left-0000.png", "right-0000.png"} <= names
        click(display, "display", 1330, 430)
        calibrator.popen.wait(30)
        assert "".join(calibrator.out).count("success: True") == 2
        for side in ("left", "right"):
            stored = parse((tmp_path / "camera_info" / f"{side}.yaml").read_text(), "yaml")
            assert stored.info.K[0] == pytest.approx(K[0, 0], rel=0.01)


def test_the_calibrators_options() -> None:
    from kame.camera.cameracalibrator import parse_options

    options = parse_options(["--size", "8x6", "--square", "0.108", "-k", "3", "--fix-principal-point",
                             "--zero-tangent-dist", "--no-service-check", "-c", "webcam"])
    assert (options.size, options.square, options.k_coefficients, options.camera_name) == (["8x6"], [0.108], 3,
                                                                                            "webcam")
    assert options.fix_principal_point and options.zero_tangent_dist and options.no_service_check
    with pytest.raises(SystemExit):
        parse_options(["--square", "0.108"])  # "You must specify one or more chessboards..."
