"""Where usb_cam's frames come from: a V4L2 device (through linuxpy), kame's test pattern
(`testsrc`) or a video file (through OpenCV). Each gives the bytes a camera sends in the chosen
pixel format, so the node converts them the same way whatever the source.

Capture is linuxpy's: pure Python over the V4L2 ioctls (formats, frame rate, the mmap, read and
userptr I/O methods usb_cam's io_method names, the cameras' controls by name), maintained, and
no compiled code. OpenCV's V4L2 backend was the other candidate; it picks the I/O method itself,
sets only the controls it has properties for, and converts frames unless told not to.

A device that cannot be opened is a CameraError whose message names the device and what to
check: that it exists, that the user is in its group (`video`), which programs hold it open.
"""

from __future__ import annotations

import errno
import grp
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.camera.pixel_formats import PixelFormat, encode
from kame.camera.testsrc import TestPattern

TESTSRC = "testsrc"


class CameraError(RuntimeError):
    """The camera cannot be opened or read; the message is what to tell the user."""


@dataclass(frozen=True)
class Settings:
    device: str
    width: int
    height: int
    format: PixelFormat
    framerate: int
    io_method: str = "mmap"


class FrameSource(Protocol):
    paced: bool  # True: read() returns at once, the node keeps the frame rate; False: the device does

    def read(self) -> bytes:
        """The next frame's bytes in the settings' pixel format."""

    def pause(self) -> None:
        """Stop capturing for now (~stop_capture): a device stops streaming."""

    def resume(self) -> None:
        """Capture again (~start_capture)."""

    def close(self) -> None:
        """Stop capturing and let the device go."""


class TestPatternSource:
    """kame's moving test pattern, frame after frame."""

    __test__ = False
    paced = True

    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.pattern = TestPattern(settings.width, settings.height)
        self.number = 0

    def read(self) -> bytes:
        picture = self.pattern.frame(self.number)
        self.number += 1
        return encode(picture, self.settings.format)

    def pause(self) -> None:
        return None  # frames are made when read: nothing runs between reads

    def resume(self) -> None:
        return None

    def close(self) -> None:
        return None


class VideoFileSource:
    """A video file's frames, scaled to the configured size, from the start again at its end."""

    paced = True

    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.cv2 = cv2_for("usb_cam's video file source")
        self.capture = self.cv2.VideoCapture(settings.device)
        if not self.capture.isOpened():
            raise CameraError(f"Cannot open video file '{settings.device}': OpenCV cannot read it "
                              "(is it a video, and does OpenCV's FFmpeg know its codec?)")

    def read(self) -> bytes:
        ok, bgr = self.capture.read()
        if not ok:  # the end: start over, as a camera never runs out
            self.capture.set(self.cv2.CAP_PROP_POS_FRAMES, 0)
            ok, bgr = self.capture.read()
            if not ok:
                raise CameraError(f"video file '{self.settings.device}' has no frames")
        size = (self.settings.width, self.settings.height)
        if (bgr.shape[1], bgr.shape[0]) != size:
            bgr = self.cv2.resize(bgr, size, interpolation=self.cv2.INTER_AREA)
        return encode(self.cv2.cvtColor(bgr, self.cv2.COLOR_BGR2RGB), self.settings.format)

    def pause(self) -> None:
        return None  # the file is read frame by frame: it waits where it is

    def resume(self) -> None:
        return None

    def close(self) -> None:
        self.capture.release()


# usb_cam 0.3.x names, and the names newer kernels give the same controls
CONTROL_NAMES = {
    "white_balance_temperature_auto": ("white_balance_temperature_auto", "white_balance_automatic"),
    "exposure_auto": ("exposure_auto", "auto_exposure"),
    "exposure_absolute": ("exposure_absolute", "exposure_time_absolute"),
    "focus_auto": ("focus_auto", "focus_automatic_continuous"),
}


class V4L2Source:
    """A V4L2 capture device through linuxpy, in the I/O method usb_cam's io_method names."""

    paced = False

    def __init__(self, settings: Settings, linuxpy_video: Any = None) -> None:
        self.settings = settings
        self.video = linuxpy_video if linuxpy_video is not None else _linuxpy_video()
        memory = {"mmap": self.video.MemoryMap, "read": self.video.ReadSource, "userptr": self.video.UserPtr}
        if settings.io_method not in memory:
            raise CameraError(f"Unknown IO method '{settings.io_method}'")
        # blocking: DQBUF waits for the next frame (linuxpy 0.25's non-blocking mmap read calls its select
        # module as a function)
        self.device = self.video.Device(settings.device, blocking=True)
        try:
            self.device.open()
        except OSError as exc:
            raise CameraError(device_problem(settings.device, exc)) from None
        try:
            self.capture = self.video.VideoCapture(self.device, buffer_type=memory[settings.io_method])
            self.capture.set_format(settings.width, settings.height, settings.format.fourcc)
            self.capture.set_fps(settings.framerate)
            self.capture.open()
        except OSError as exc:
            self.device.close()
            raise CameraError(device_problem(settings.device, exc)) from None

    def set_control(self, name: str, value: int) -> bool:
        """Set the control usb_cam calls `name` (or its newer name); False if the device has none."""
        for candidate in CONTROL_NAMES.get(name, (name,)):
            try:
                control = self.device.controls[candidate]
            except KeyError:
                continue
            control.value = value
            return True
        return False

    def read(self) -> bytes:
        try:
            frame = self.capture.buffer.read()
        except OSError as exc:
            raise CameraError(f"reading '{self.settings.device}' failed: {exc}") from None
        return bytes(frame.data)

    def pause(self) -> None:
        """STREAMOFF and the buffers freed, as usb_cam's stop_capturing."""
        self.capture.close()

    def resume(self) -> None:
        """The buffers queued again and STREAMON, as usb_cam's start_capturing."""
        try:
            self.capture.open()
        except OSError as exc:
            raise CameraError(device_problem(self.settings.device, exc)) from None

    def close(self) -> None:
        try:
            self.capture.close()
        finally:
            self.device.close()


def _linuxpy_video() -> Any:
    try:
        import linuxpy.video.device as video
    except ImportError:
        raise CameraError("capturing from a V4L2 camera needs linuxpy: pip install 'kame[camera]' "
                          "(video_device:=testsrc or a video file work without it)") from None
    return video


def open_source(settings: Settings) -> FrameSource:
    """The source usb_cam's video_device names: testsrc, a video file, or a V4L2 device."""
    try:
        if settings.device == TESTSRC:
            return TestPatternSource(settings)
        if not settings.device.startswith("/dev/") and Path(settings.device).is_file():
            return VideoFileSource(settings)
    except OpenCVMissing as exc:
        raise CameraError(str(exc)) from None
    return V4L2Source(settings)


def holders(device: str, proc: Path = Path("/proc")) -> list[tuple[int, str]]:
    """(pid, program name) of every process with `device` open, as far as /proc lets us see."""
    target = os.path.realpath(device)
    found: list[tuple[int, str]] = []
    for entry in _pids(proc):
        try:
            links = [os.readlink(fd) for fd in (entry / "fd").iterdir()]
            if target in links:
                found.append((int(entry.name), (entry / "comm").read_text().strip()))
        except OSError:  # gone, or not ours to look at
            continue
    return found


def _pids(proc: Path) -> Iterable[Path]:
    try:
        return [entry for entry in proc.iterdir() if entry.name.isdigit() and int(entry.name) != os.getpid()]
    except OSError:
        return []


def device_problem(device: str, exc: OSError | None = None) -> str:
    """One message naming the device and what to check, for an open or start that failed."""
    path = Path(device)
    if not path.exists() or (exc is not None and exc.errno == errno.ENOENT):
        return (f"Cannot open '{device}': it does not exist. Is the camera plugged in? `ls /dev/video*` lists "
                f"the video devices; video_device:=testsrc is kame's test camera")
    if exc is not None and exc.errno in (errno.EACCES, errno.EPERM):
        group = _group_of(path)
        return (f"Cannot open '{device}': permission denied. It belongs to group '{group}': add yourself with "
                f"`sudo usermod -aG {group} $USER`, then log in again")
    if exc is not None and exc.errno == errno.EBUSY:
        held = holders(device)
        by = ", ".join(f"{name} (pid {pid})" for pid, name in held) or "another program (not one we may see)"
        return f"'{device}' is busy: it is held by {by}. Close it there, or choose another video_device"
    reason = f": {exc.strerror or exc}" if exc is not None else ""
    return f"Cannot open '{device}'{reason}. Is it a V4L2 capture device (`v4l2-ctl --list-devices`)?"


def _group_of(path: Path) -> str:
    try:
        return grp.getgrgid(path.stat().st_gid).gr_name
    except (KeyError, OSError):
        return "video"
