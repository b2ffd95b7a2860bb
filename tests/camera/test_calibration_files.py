"""camera_calibration_parsers and camera_info_manager: YAML and INI round trips, camera_calibration's
own ost.yaml layout, Debian's parser reading kame's files, `rosrun camera_calibration_parsers
convert`, the calibration URLs, and live: usb_cam loading its calibration and set_camera_info
writing it."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from kame.camera.calibration_files import Calibration, CalibrationFileError, dump, parse
from kame.camera.info_url import CalibrationURLError, resolve
from sensor_msgs.msg import CameraInfo
from tests.libs.debian import SYSTEM_PYTHON, debian_env, has
from tests.support import Proc
from tests.turtlesim.sim import master

PROBE = Path(__file__).with_name("probe.py")
K = [612.5, 0.0, 321.25, 0.0, 611.75, 238.5, 0.0, 0.0, 1.0]
D = [-0.21, 0.043, 0.0012, -0.0007, 0.0]
R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
P = [580.0, 0.0, 320.5, 0.0, 0.0, 585.25, 240.0, 0.0, 0.0, 0.0, 1.0, 0.0]
OST_YAML = """image_width: 640
image_height: 480
camera_name: narrow_stereo
camera_matrix:
  rows: 3
  cols: 3
  data: [612.5  ,   0.     , 321.25 ,
           0.     , 611.75 , 238.5  ,
           0.     ,   0.     ,   1.     ]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.210000, 0.043000, 0.001200, -0.000700, 0.000000]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1., 0., 0.,
         0., 1., 0.,
         0., 0., 1.]
projection_matrix:
  rows: 3
  cols: 4
  data: [580.  ,   0.  , 320.5 ,   0.  ,
           0.  , 585.25, 240.  ,   0.  ,
           0.  ,   0.  ,   1.  ,   0.  ]
"""


def calibration() -> Calibration:
    return Calibration("head_camera", CameraInfo(width=640, height=480, distortion_model="plumb_bob",
                                                 K=K, D=D, R=R, P=P))


def fields(info: CameraInfo) -> tuple[object, ...]:
    return (info.width, info.height, info.distortion_model, list(info.K), list(info.D), list(info.R), list(info.P))


@pytest.mark.parametrize("format", ["yaml", "ini"])
def test_round_trip(format: str) -> None:
    back = parse(dump(calibration(), format), format)
    assert back.camera_name == "head_camera"
    assert fields(back.info) == fields(calibration().info)


def test_camera_calibrations_ost_yaml_reads() -> None:
    back = parse(OST_YAML, "yaml")
    assert back.camera_name == "narrow_stereo" and fields(back.info) == fields(calibration().info)


def test_a_broken_file_says_what_is_wrong() -> None:
    with pytest.raises(CalibrationFileError, match="camera_matrix is 3x2, 3x3 expected"):
        parse(OST_YAML.replace("  cols: 3\n  data: [612.5", "  cols: 2\n  data: [612.5"), "yaml")
    with pytest.raises(CalibrationFileError, match="'projection' entry is missing"):
        parse(dump(calibration(), "ini").split("projection")[0], "ini")


@pytest.mark.skipif(not has("camera_calibration_parsers"), reason="Debian's python3-camera-calibration-parsers")
@pytest.mark.parametrize("suffix", [".yaml", ".ini"])
def test_debians_parser_reads_kames_files(tmp_path: Path, suffix: str) -> None:
    path = tmp_path / f"head_camera{suffix}"
    path.write_text(dump(calibration(), suffix.lstrip(".")))
    script = ("import json, sys, camera_calibration_parsers as c\n"
              "name, info = c.readCalibration(sys.argv[1])\n"
              "print(json.dumps([name, info.width, info.height, info.distortion_model, list(info.K), list(info.D),"
              " list(info.R), list(info.P)]))\n")
    result = subprocess.run([str(SYSTEM_PYTHON), "-c", script, str(path)], capture_output=True, text=True,
                            env=debian_env(), timeout=60)
    assert result.returncode == 0, result.stderr
    name, *values = json.loads(result.stdout)
    assert name == "head_camera"
    expected = fields(calibration().info)
    assert values[:3] == list(expected[:3])
    for got, want in zip(values[3:], expected[3:], strict=True):  # Debian's INI reader rounds in the last bit
        assert got == pytest.approx(want, rel=1e-15, abs=1e-18)


def test_the_module_users_import(tmp_path: Path) -> None:
    import camera_calibration_parsers

    path = tmp_path / "cam.yml"
    assert camera_calibration_parsers.writeCalibration(str(path), "cam", calibration().info)
    read = camera_calibration_parsers.readCalibration(str(path))
    assert read is not None and read[0] == "cam" and list(read[1].K) == K
    assert camera_calibration_parsers.readCalibration(str(tmp_path / "missing.yaml")) is None


def test_convert(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        (tmp_path / "in.yaml").write_text(OST_YAML)
        out = sim.run("rosrun", "camera_calibration_parsers", "convert", "in.yaml", "out.ini").stdout
        assert out.strip() == "Saved out.ini"
        sim.run("rosrun", "camera_calibration_parsers", "convert", "out.ini", "back.yml")
        back = parse((tmp_path / "back.yml").read_text(), "yaml")
        assert back.camera_name == "narrow_stereo" and fields(back.info) == fields(calibration().info)
        usage = sim.run("rosrun", "camera_calibration_parsers", "convert").stdout
        assert usage.startswith("Usage: convert input.yml output.ini")


def test_calibration_urls(tmp_path: Path) -> None:
    def find(package: str) -> str | None:
        return str(tmp_path / package) if package == "my_camera" else None

    assert resolve("", "head_camera", "/home/u/.ros", find) == "/home/u/.ros/camera_info/head_camera.yaml"
    assert resolve("file:///etc/cams/${NAME}.ini", "left", "/r", find) == "/etc/cams/left.ini"
    assert resolve("package://my_camera/info/${NAME}.yaml", "c", "/r", find) == f"{tmp_path}/my_camera/info/c.yaml"
    with pytest.raises(CalibrationURLError, match="Calibration package missing: other"):
        resolve("package://other/c.yaml", "c", "/r", find)
    with pytest.raises(CalibrationURLError, match=r"Invalid camera calibration URL: http://x/c\.yaml"):
        resolve("http://x/c.yaml", "c", "/r", find)


SET_INFO = """
import sys
import rospy
from sensor_msgs.msg import CameraInfo
from sensor_msgs.srv import SetCameraInfo
rospy.init_node("committer")
rospy.wait_for_service("/usb_cam/set_camera_info", 30)
info = CameraInfo(width=64, height=48, distortion_model="plumb_bob", K=[50, 0, 32, 0, 51, 24, 0, 0, 1],
                  D=[0.1, 0, 0, 0, 0], R=[1, 0, 0, 0, 1, 0, 0, 0, 1], P=[50, 0, 32, 0, 0, 51, 24, 0, 0, 0, 1, 0])
reply = rospy.ServiceProxy("/usb_cam/set_camera_info", SetCameraInfo)(info)
print(reply.success, repr(reply.status_message), flush=True)
"""


def test_usb_cam_loads_and_stores_its_calibration(tmp_path: Path) -> None:
    path = tmp_path / "cams" / "head_camera.yaml"
    path.parent.mkdir()
    path.write_text(OST_YAML.replace("narrow_stereo", "head_camera"))
    with master(tmp_path) as sim:
        sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_framerate:=10",
                  f"_camera_info_url:=file://{tmp_path}/cams/${{NAME}}.yaml")
        info = json.loads(sim.run(sys.executable, str(PROBE), "info", "/usb_cam/camera_info").stdout)
        assert info["K"] == K and info["D"] == D and info["frame_id"] == "head_camera"
        committer = Proc([sys.executable, "-c", SET_INFO], sim.env, cwd=sim.home)
        sim.procs.append(committer)
        committer.popen.wait(60)
        out, err = committer.stop()
        assert out.strip() == "True ''", out + err
        stored = parse(path.read_text(), "yaml")
        assert stored.camera_name == "head_camera" and list(stored.info.K) == [50, 0, 32, 0, 51, 24, 0, 0, 1]
        info = json.loads(sim.run(sys.executable, str(PROBE), "info", "/usb_cam/camera_info").stdout)
        assert info["width"] == 64 and info["K"][0] == 50.0  # published from then on


def test_an_uncalibrated_camera_warns_and_publishes_its_size(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        cam = sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_framerate:=10",
                        "_image_width:=160", "_image_height:=120")
        info = json.loads(sim.run(sys.executable, str(PROBE), "info", "/usb_cam/camera_info").stdout)
        assert (info["width"], info["height"], info["K"][0]) == (160, 120, 0.0)
        cam.popen.send_signal(2)
        cam.popen.wait(15)
        assert f"Camera calibration file {tmp_path}/camera_info/head_camera.yaml not found." in "".join(cam.err)
