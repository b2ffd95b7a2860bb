"""image_view: the window under Xvfb showing usb_cam's test pattern (screenshot in the tour), and
offscreen: right click and the `s` key save the shown picture under filename_format, a left
click warns once, autosize fits the window to the picture."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kame.camera.pictures import format_filename
from kame.camera.testsrc import BARS
from kame.camera.viewer_model import LEFT_CLICK_WARNING, ViewerModel, ViewerSettings
from tests.support import Proc
from tests.support.tour import shoot
from tests.turtlesim.sim import BIN, master
from tests.turtlesim.xserver import Screenshot, xvfb

pytest.importorskip("cv2")
QtCore = pytest.importorskip("PySide6.QtCore")


def test_filename_formats_fill_as_boost_format_does() -> None:
    assert format_filename("frame%04i.jpg", 7) == "frame0007.jpg"
    assert format_filename("left%04i.%s", 12, "png") == "left0012.png"
    assert format_filename("left%04i.%s", 12, "png", "ignored") == "left0012.png"
    assert format_filename("still.jpg", 3) == "still.jpg"


def shows_the_bars(shot: Screenshot) -> bool:
    """The test pattern's colour bars across the window (yuyv blurs their edges a little)."""
    row = shot.height // 2
    seen = {tuple(int(v) for v in bar) for bar in BARS[:7]
            if any(max(abs(a - int(b)) for a, b in zip(shot.rgb(x, row), bar, strict=True)) < 30
                   for x in range(0, shot.width, 4))}
    return len(seen) >= 6


def test_image_view_shows_usb_cams_test_pattern(tmp_path: Path) -> None:
    with xvfb("800x600") as display, master(tmp_path) as sim:
        env = {**sim.env, "DISPLAY": display, "QT_QPA_PLATFORM": "xcb"}
        sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_pixel_format:=yuyv", "_framerate:=15",
                  "_image_width:=320", "_image_height:=240")
        sim.start("image_view", "image_view", "image:=/usb_cam/image_raw", "_autosize:=true", env=env)
        shot = shoot(display, "/usb_cam/image_raw", "image_view_testsrc", shows_the_bars)
        assert (shot.width, shot.height) == (320, 240)  # autosize: the window is the picture's size


def test_window_name_and_compressed_transport(tmp_path: Path) -> None:
    with xvfb("800x600") as display, master(tmp_path) as sim:
        env = {**sim.env, "DISPLAY": display, "QT_QPA_PLATFORM": "xcb"}
        sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_pixel_format:=mjpeg", "_framerate:=15",
                  "_image_width:=320", "_image_height:=240")
        sim.start("image_view", "image_view", "image:=/usb_cam/image_raw", "compressed", "_window_name:=webcam",
                  env=env)
        shoot(display, "webcam", "image_view_compressed", shows_the_bars)


def test_right_click_and_s_save_the_shown_picture(qtbot, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    from PySide6.QtCore import QPoint, Qt

    from kame.camera.image_view_window import ImageViewWindow

    model = ViewerModel(ViewerSettings("/cam/image", filename_format=str(tmp_path / "shot%02i.png"), autosize=True))
    picture = np.zeros((30, 40, 3), np.uint8)
    picture[:, 20:] = (0, 0, 255)  # BGR: red on the right
    waiting: list[np.ndarray | None] = [picture]
    saved: list[str] = []
    warnings: list[str] = []

    def take() -> np.ndarray | None:
        shown = waiting.pop() if waiting else None
        if shown is not None:
            model.show(shown)
        return shown

    def save() -> None:
        name = model.next_filename()
        assert name is not None
        saved.append(name)

    window = ImageViewWindow(model, take, save, warnings.append)
    qtbot.addWidget(window)
    window.show()
    window.frame_ready.emit()
    qtbot.waitUntil(lambda: window.image is not None)
    assert window.windowTitle() == "/cam/image" and window.picture.size().toTuple() == (40, 30)
    assert window.image is not None and window.image.pixelColor(30, 10).red() == 255
    qtbot.mouseClick(window.picture, Qt.MouseButton.RightButton, pos=QPoint(5, 5))
    qtbot.keyClick(window, "s")
    assert saved == [str(tmp_path / "shot00.png"), str(tmp_path / "shot01.png")]
    qtbot.mouseClick(window.picture, Qt.MouseButton.LeftButton, pos=QPoint(5, 5))
    qtbot.mouseClick(window.picture, Qt.MouseButton.LeftButton, pos=QPoint(5, 5))
    assert warnings == [LEFT_CLICK_WARNING]


def test_the_lessons_launch_file(tmp_path: Path) -> None:
    """`roslaunch usb_cam usb_cam-test.launch`, as the course's slide has it, with kame's test camera."""
    with xvfb("800x600") as display, master(tmp_path) as sim:
        env = {**sim.env, "DISPLAY": display, "QT_QPA_PLATFORM": "xcb"}
        launch = Proc([str(BIN / "roslaunch"), "usb_cam", "usb_cam-test.launch", "video_device:=testsrc"], env,
                      cwd=sim.home)
        sim.procs.append(launch)
        shot = shoot(display, "/usb_cam/image_raw", "usb_cam_test_launch", shows_the_bars)
        assert (shot.width, shot.height) == (640, 480)
