"""image_view's image_saver, video_recorder and extract_images on usb_cam's test pattern."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kame.camera.calibration_files import parse
from tests.turtlesim.sim import Sim, master

cv2 = pytest.importorskip("cv2")
from kame.camera.testsrc import SCROLL, TestPattern, frame_number_box  # noqa: E402 - needs OpenCV

WIDTH, HEIGHT = 160, 120


def camera(sim: Sim, rate: int = 15) -> None:
    sim.start("usb_cam", "usb_cam_node", "_video_device:=testsrc", "_pixel_format:=yuyv", f"_framerate:={rate}",
              f"_image_width:={WIDTH}", f"_image_height:={HEIGHT}")


def is_the_pattern(picture: np.ndarray) -> bool:
    """Whether a saved BGR picture is one of usb_cam's testsrc frames, up to JPEG's losses. Which
    frame comes first depends on when the saver or the recorder started listening, so every
    scroll offset is tried; the counter's box is left out."""
    pattern = TestPattern(WIDTH, HEIGHT)
    _, _, box_right, box_bottom = frame_number_box(WIDTH, HEIGHT)
    outside_the_box = np.ones((HEIGHT, WIDTH), bool)
    outside_the_box[:box_bottom, :box_right] = False
    rgb = picture[:, :, ::-1].astype(int)
    return min(float(np.abs(rgb - pattern.frame(n).astype(int))[outside_the_box].mean())
               for n in range(WIDTH // SCROLL)) < 12


def test_image_saver_saves_every_image_with_its_calibration(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        camera(sim)
        saver = sim.start("image_view", "image_saver", "image:=/usb_cam/image_raw",
                          f"_filename_format:={tmp_path}/left%04i.%s")
        saver.wait_line(f"Saved image {tmp_path}/left0010.jpg", timeout=30)
        # as upstream's, the line comes before the image's .ini is written; the next image's line
        # after it
        saver.wait_line(f"Saved image {tmp_path}/left0011.jpg", timeout=30)
        picture = cv2.imread(str(tmp_path / "left0000.jpg"))
        assert picture.shape == (120, 160, 3)
        assert is_the_pattern(picture)
        # images that came before the first camera_info are saved alone, the others with it
        calibrations = sorted(tmp_path.glob("left*.ini"))
        assert calibrations and tmp_path / "left0010.ini" in calibrations
        calibration = parse((tmp_path / "left0010.ini").read_text(), "ini")
        assert (calibration.camera_name, calibration.info.width, calibration.info.height) == ("camera", 160, 120)


def test_image_saver_saves_on_request(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        camera(sim)
        saver = sim.start("image_view", "image_saver", "__name:=saver", "image:=/usb_cam/image_raw",
                          "_save_all_image:=false", f"_filename_format:={tmp_path}/still%02i.png")
        for number in range(2):
            sim.run("rosservice", "call", "--wait", "/saver/save")
            saver.wait_line(f"Saved image {tmp_path}/still{number:02d}.png")
        # the camera sends 15 images a second: only the two asked for were saved
        assert sorted(path.name for path in tmp_path.glob("still*.png")) == ["still00.png", "still01.png"]


def test_video_recorder_writes_a_video_opencv_reads(tmp_path: Path) -> None:
    video = tmp_path / "lesson.avi"
    with master(tmp_path) as sim:
        camera(sim, rate=20)
        recorder = sim.start("image_view", "video_recorder", "image:=/usb_cam/image_raw", f"_filename:={video}",
                             "_fps:=10")
        recorder.wait_line("Starting to record MJPG video at [160 x 120]@10fps. Press Ctrl+C to stop recording.")
        sim.run("rostopic", "echo", "-n", "20", "/usb_cam/image_raw/header/seq")  # a second of images
        out, _ = recorder.stop()
        assert f"Video saved as {video}" in out
    capture = cv2.VideoCapture(str(video))
    frames = []
    while True:
        ok, frame = capture.read()
        if not ok:
            break
        frames.append(frame)
    capture.release()
    assert len(frames) >= 5 and frames[0].shape == (120, 160, 3)
    assert is_the_pattern(frames[0]) and is_the_pattern(frames[-1])


def test_extract_images(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        camera(sim)
        extractor = sim.start("image_view", "extract_images", "image:=/usb_cam/image_raw", "_sec_per_frame:=0.2",
                              f"_filename_format:={tmp_path}/frame%04d.jpg")
        extractor.wait_line(f"Saved image {tmp_path}/frame0002.jpg", timeout=30)
        assert cv2.imread(str(tmp_path / "frame0001.jpg")).shape == (120, 160, 3)
