"""usb_cam's capture layer (kame.camera.sources.V4L2Source, on linuxpy) against a fake V4L2
webcam answering linuxpy's ioctls (tests/camera/fake_v4l2.py): the format and frame rate asked
for, mmap buffers queued and dequeued frame after frame, usb_cam's controls set by name (and by
the newer kernels' names), an unknown I/O method, and a busy device's message."""

from __future__ import annotations

from pathlib import Path

import pytest

from kame.camera.pixel_formats import FORMATS, decode, encode
from kame.camera.sources import CameraError, Settings, V4L2Source
from kame.camera.testsrc import TestPattern
from kame.camera.usb_cam_node import DEFAULTS, apply_controls

pytest.importorskip("cv2")
video = pytest.importorskip("linuxpy.video.device")
import linuxpy.ioctl  # noqa: E402 - after the skip

from tests.camera.fake_v4l2 import FakeCamera  # noqa: E402


@pytest.fixture
def camera(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> FakeCamera:
    pattern = TestPattern(64, 48)
    frames = [encode(pattern.frame(number), FORMATS["yuyv"]) for number in range(3)]
    fake = FakeCamera(tmp_path / "video0", frames)

    class FakeFcntl:
        ioctl = staticmethod(fake.ioctl)

    monkeypatch.setattr(linuxpy.ioctl, "fcntl", FakeFcntl)
    return fake


def settings(camera: FakeCamera, io_method: str = "mmap") -> Settings:
    return Settings(str(camera.path), 64, 48, FORMATS["yuyv"], 15, io_method)


def test_mmap_capture_gives_the_frames_in_order(camera: FakeCamera) -> None:
    source = V4L2Source(settings(camera))
    try:
        assert (camera.width, camera.height, camera.fps, camera.streaming) == (64, 48, 15.0, True)
        assert camera.fourcc == int.from_bytes(b"YUYV", "little")
        assert camera.buffers >= 1 and "QBUF" in camera.calls
        frames = [source.read() for _ in range(4)]
    finally:
        source.close()
    assert frames[0] == camera.frames[0] and frames[1] == camera.frames[1] and frames[3] == camera.frames[0]
    assert not camera.streaming  # STREAMOFF at close
    picture = decode(frames[1], FORMATS["yuyv"], 64, 48)
    assert picture.shape == (48, 64, 3)


def test_stop_and_start_capture_stop_and_start_the_stream(camera: FakeCamera) -> None:
    source = V4L2Source(settings(camera))
    try:
        source.read()
        source.pause()
        assert not camera.streaming
        source.resume()
        assert camera.streaming and source.read() == camera.frames[1]
    finally:
        source.close()


def test_usb_cams_controls_are_set_by_name(camera: FakeCamera) -> None:
    source = V4L2Source(settings(camera))
    try:
        params = {**DEFAULTS, "brightness": 200, "contrast": 40, "gain": 7, "auto_white_balance": False,
                  "white_balance": 5000}
        apply_controls(source, params)
    finally:
        source.close()
    assert camera.value("Brightness") == 200 and camera.value("Contrast") == 40 and camera.value("Gain") == 7
    assert camera.value("Saturation") == 64  # -1: left alone
    # white_balance_temperature_auto, as usb_cam 0.3 calls it, is white_balance_automatic on newer kernels
    assert camera.value("White Balance, Automatic") == 0 and camera.value("White Balance Temperature") == 5000


def test_a_busy_camera_names_what_to_check(camera: FakeCamera) -> None:
    camera.busy = True
    with pytest.raises(CameraError, match=f"'{camera.path}' is busy: it is held by"):
        V4L2Source(settings(camera))


def test_an_unknown_io_method_is_refused(camera: FakeCamera) -> None:
    with pytest.raises(CameraError, match="Unknown IO method 'dma'"):
        V4L2Source(settings(camera, "dma"))
