"""usb_cam: the pixel formats, the test pattern, the no-camera messages, and the node live with
testsrc and a video file (its rate, pictures, camera_info, start/stop_capture services)."""

from __future__ import annotations

import errno
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kame.camera.pixel_formats import FORMATS, decode, encode
from kame.camera.sources import device_problem, holders
from kame.camera.testsrc import BARS, SCROLL, TestPattern, frame_number_box
from tests.support import Proc
from tests.turtlesim.sim import Sim, master

cv2 = pytest.importorskip("cv2")
PROBE = Path(__file__).with_name("probe.py")


def probe_images(sim: Sim, topic: str, count: int) -> tuple[dict[str, Any], Any]:
    out = sim.home / f"probe{len(sim.procs)}.npz"
    proc = Proc([sys.executable, str(PROBE), "images", topic, str(count), str(out)], sim.env, cwd=sim.home)
    sim.procs.append(proc)
    proc.popen.wait(60)
    stdout, stderr = proc.stop()
    assert proc.popen.returncode == 0, stdout + stderr
    return json.loads(stdout.splitlines()[-1]), np.load(out)


@pytest.mark.parametrize("name", sorted(FORMATS))
def test_every_pixel_format_gives_the_picture_back(name: str) -> None:
    picture = TestPattern(64, 48).frame(3)
    format = FORMATS[name]
    back = decode(encode(picture, format), format, 64, 48)
    if format.encoding == "mono8":
        assert back.shape == (48, 64)
        assert np.abs(back.astype(int) - cv2.cvtColor(picture, cv2.COLOR_RGB2GRAY)).max() <= 4
    else:
        assert back.shape == (48, 64, 3)
        # YUV 4:2:2 halves the colour's resolution and jpeg is lossy: most pixels match, the bars' edges blur
        error = np.abs(back.astype(int) - picture).max(axis=2)
        if name == "rgb24":
            assert np.array_equal(back, picture)
        else:
            assert (error <= 24).mean() >= 0.85, (error <= 24).mean()


def test_the_test_pattern_scrolls_and_counts() -> None:
    pattern = TestPattern(160, 120)
    first, second = pattern.frame(0), pattern.frame(1)
    x0, y0, x1, y1 = frame_number_box(160, 120)
    row = y1 + 5
    assert (first[row, 0] == BARS[0]).all() and (first[row, 159] == BARS[7]).all()
    assert np.array_equal(second[row, :-SCROLL], first[row, SCROLL:])  # the bars moved left
    assert (first[y0:y1, x0:x1] == 0).any() and (first[y0:y1, x0:x1] == 255).any()  # white digits on black
    assert not np.array_equal(first[y0:y1, x0:x1], second[y0:y1, x0:x1])  # the counter changed


def test_a_missing_device_says_what_to_check(tmp_path: Path) -> None:
    message = device_problem(str(tmp_path / "video7"))
    assert f"'{tmp_path / 'video7'}': it does not exist" in message and "testsrc" in message
    denied = device_problem("/dev/null", OSError(errno.EACCES, "Permission denied"))
    assert "permission denied" in denied and "usermod -aG" in denied


def test_a_busy_device_names_who_holds_it(tmp_path: Path) -> None:
    device = tmp_path / "video0"
    device.write_bytes(b"")
    holder = subprocess.Popen([sys.executable, "-c", "import sys; f = open(sys.argv[1]); print(1, flush=True); "
                               "sys.stdin.read()", str(device)], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    try:
        assert holder.stdout is not None and holder.stdout.readline()  # the file is open now
        assert (holder.pid, "python3") in [(pid, name if not name.startswith("python") else "python3")
                                           for pid, name in holders(str(device))]
        message = device_problem(str(device), OSError(errno.EBUSY, "Device or resource busy"))
        assert f"'{device}' is busy: it is held by python" in message and f"(pid {holder.pid})" in message
    finally:
        holder.kill()
        holder.wait()


def test_testsrc_publishes_at_its_framerate(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_pixel_format:=yuyv", "_framerate:=20",
                  "_image_width:=320", "_image_height:=240", "_camera_frame_id:=usb_cam")
        fields, pictures = probe_images(sim, "/usb_cam/image_raw", 41)
        assert (fields["encoding"], fields["width"], fields["height"], fields["frame_id"]) == (
            "rgb8", 320, 240, "usb_cam")
        assert 18.0 <= fields["rate"] <= 22.0, fields
        first = pictures["first"]
        row = first[frame_number_box(320, 240)[3] + 5].astype(int)
        nearest = np.abs(row[:, None, :] - BARS[None].astype(int)).max(axis=2).min(axis=1)
        assert (nearest <= 30).mean() >= 0.9  # the colour bars, through yuyv and back (edges blur)
        info = json.loads(sim.run(sys.executable, str(PROBE), "info", "/usb_cam/camera_info").stdout)
        assert (info["width"], info["height"], info["frame_id"]) == (320, 240, "usb_cam")


def test_stop_and_start_capture(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_pixel_format:=mono8", "_framerate:=30",
                  "_image_width:=64", "_image_height:=48")
        assert probe_images(sim, "/usb_cam/image_raw", 2)[0]["encoding"] == "mono8"
        sim.run("rosservice", "call", "/usb_cam/stop_capture")
        waiting = Proc([sys.executable, str(PROBE), "images", "/usb_cam/image_raw", "1", str(tmp_path / "w.npz")],
                       sim.env, cwd=sim.home)
        sim.procs.append(waiting)
        with pytest.raises(subprocess.TimeoutExpired):  # nothing comes while capture is stopped
            waiting.popen.wait(2)
        sim.run("rosservice", "call", "/usb_cam/start_capture")
        assert waiting.popen.wait(30) == 0


def test_a_video_file_is_a_camera(tmp_path: Path) -> None:
    video = tmp_path / "clip.avi"
    writer = cv2.VideoWriter(str(video), cv2.VideoWriter_fourcc(*"MJPG"), 10, (160, 120))
    pattern = TestPattern(160, 120)
    for number in range(10):
        writer.write(cv2.cvtColor(pattern.frame(number), cv2.COLOR_RGB2BGR))
    writer.release()
    with master(tmp_path) as sim:
        sim.start("usb_cam", "usb_cam_node", f"_video_device:={video}", "_pixel_format:=rgb24", "_framerate:=15",
                  "_image_width:=80", "_image_height:=60")
        fields, pictures = probe_images(sim, "/usb_cam/image_raw", 12)  # more than the file has: it loops
        assert (fields["width"], fields["height"]) == (80, 60)
        assert np.abs(pictures["first"][40, 2].astype(int) - BARS[0]).max() < 40  # white bar at the left


def test_no_camera_is_one_clear_line(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        missing = tmp_path / "video9"
        proc = sim.start("usb_cam", "usb_cam_node", f"_video_device:={missing}")
        proc.popen.wait(30)
        out, err = proc.stop()
        assert proc.popen.returncode == 1
        assert f"Cannot open '{missing}': it does not exist" in out + err and "Traceback" not in out + err


def test_without_opencv_one_line_names_the_feature(tmp_path: Path) -> None:
    hidden = tmp_path / "hidden"
    (hidden / "cv2").mkdir(parents=True)
    (hidden / "cv2" / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'cv2'\", name='cv2')\n")
    with master(tmp_path) as sim:
        env = {**sim.env, "PYTHONPATH": str(hidden)}
        camera = sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", env=env)
        viewer = sim.start("image_view", "image_view", "image:=/usb_cam/image_raw", env=env)
        install = "needs OpenCV: pip install 'kame[camera]'"
        for proc, line in ((camera, f"the test pattern (video_device:=testsrc) {install}"),
                           (viewer, f"image_view {install}")):
            proc.popen.wait(30)
            out, err = proc.stop()
            assert proc.popen.returncode == 1 and line in out + err and "Traceback" not in out + err, out + err
