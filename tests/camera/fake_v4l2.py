"""A V4L2 capture device for the capture layer's tests: the answers a UVC webcam's driver gives
to the ioctls linuxpy makes (QUERYCAP, S_FMT/G_FMT, S_PARM, REQBUFS, QUERYBUF, QBUF/DQBUF,
STREAMON/OFF, QUERY_EXT_CTRL, G/S_EXT_CTRLS), given in place of fcntl.ioctl, over a regular file
whose pages stand for the driver's mmap buffers. No device node can be made on these machines;
this is what was tested instead of a camera (the README says so).

Each DQBUF "captures" the next of `frames` into the dequeued buffer. `busy` makes S_FMT fail
with EBUSY, as a device another program streams from does.
"""

from __future__ import annotations

import errno
import mmap
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import linuxpy.video.device as video
import linuxpy.video.raw as raw

BUFFER_SPACE = 8 * 1024 * 1024  # bytes of the file standing for the driver's buffers


@dataclass
class Control:
    id: int
    name: str
    type: int
    minimum: int
    maximum: int
    default: int
    value: int


def uvc_controls() -> list[Control]:
    """A webcam's user controls, with the kernel's ids and names."""
    cid = 0x00980900  # V4L2_CID_BASE
    integer, boolean = int(video.ControlType.INTEGER), int(video.ControlType.BOOLEAN)
    return [Control(cid + 0, "Brightness", integer, 0, 255, 128, 128),
            Control(cid + 1, "Contrast", integer, 0, 255, 32, 32),
            Control(cid + 2, "Saturation", integer, 0, 255, 64, 64),
            Control(cid + 12, "White Balance, Automatic", boolean, 0, 1, 1, 1),
            Control(cid + 19, "Gain", integer, 0, 100, 0, 0),
            Control(cid + 26, "White Balance Temperature", integer, 2800, 6500, 4600, 4600),
            Control(cid + 27, "Sharpness", integer, 0, 7, 3, 3)]


@dataclass
class FakeCamera:
    path: Path
    frames: list[bytes]
    busy: bool = False
    controls: list[Control] = field(default_factory=uvc_controls)
    width: int = 0
    height: int = 0
    fourcc: int = 0
    fps: float = 0.0
    buffers: int = 0
    queued: list[int] = field(default_factory=list)
    streaming: bool = False
    captured: int = 0
    calls: list[str] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.path.write_bytes(b"\0" * BUFFER_SPACE)

    @property
    def buffer_size(self) -> int:
        return -(-max(self.width * self.height * 2, 1) // mmap.PAGESIZE) * mmap.PAGESIZE

    def ioctl(self, fd: int, request: Any, arg: Any = None, *rest: Any) -> Any:
        name = raw.IOC(request).name
        self.calls.append(name)
        handler = getattr(self, "_" + name.lower(), None)
        if handler is None:
            raise OSError(errno.ENOTTY, f"{name}: not a request this fake answers")
        handler(fd, arg)
        return 0

    def _querycap(self, fd: int, caps: Any) -> None:
        caps.driver, caps.card, caps.bus_info = b"uvcvideo", b"Fake Webcam", b"usb-0000:00:14.0-1"
        flags = video.Capability.VIDEO_CAPTURE | video.Capability.STREAMING | video.Capability.READWRITE
        caps.device_caps = int(flags)
        caps.capabilities = int(flags | video.Capability.DEVICE_CAPS)

    def _s_fmt(self, fd: int, fmt: Any) -> None:
        if self.busy:
            raise OSError(errno.EBUSY, os.strerror(errno.EBUSY))
        self.width, self.height, self.fourcc = fmt.fmt.pix.width, fmt.fmt.pix.height, fmt.fmt.pix.pixelformat
        self._g_fmt(fd, fmt)

    def _g_fmt(self, fd: int, fmt: Any) -> None:
        fmt.fmt.pix.width, fmt.fmt.pix.height, fmt.fmt.pix.pixelformat = self.width, self.height, self.fourcc
        fmt.fmt.pix.bytesperline = self.width * 2
        fmt.fmt.pix.sizeimage = self.width * self.height * 2

    def _s_parm(self, fd: int, parm: Any) -> None:
        frame = parm.parm.capture.timeperframe
        self.fps = frame.denominator / frame.numerator

    def _reqbufs(self, fd: int, request: Any) -> None:
        self.buffers = min(request.count, BUFFER_SPACE // self.buffer_size)
        request.count = self.buffers
        self.queued.clear()

    def _querybuf(self, fd: int, buffer: Any) -> None:
        buffer.length = self.buffer_size
        buffer.m.offset = buffer.index * self.buffer_size

    def _qbuf(self, fd: int, buffer: Any) -> None:
        self.queued.append(buffer.index)

    def _dqbuf(self, fd: int, buffer: Any) -> None:
        if not self.streaming or not self.queued:
            raise OSError(errno.EINVAL, "not streaming")
        index = self.queued.pop(0)
        frame = self.frames[self.captured % len(self.frames)]
        with open(self.path, "r+b") as memory:
            memory.seek(index * self.buffer_size)
            memory.write(frame)
        buffer.index, buffer.bytesused, buffer.sequence = index, len(frame), self.captured
        self.captured += 1

    def _streamon(self, fd: int, kind: Any) -> None:
        self.streaming = True

    def _streamoff(self, fd: int, kind: Any) -> None:
        self.streaming = False

    def _query_ext_ctrl(self, fd: int, query: Any) -> None:
        after = query.id & ~int(video.ControlFlag.NEXT_CTRL | video.ControlFlag.NEXT_COMPOUND)
        following = [control for control in self.controls if control.id > after]
        if not following:
            raise OSError(errno.EINVAL, "no more controls")
        control = min(following, key=lambda control: control.id)
        query.id, query.type, query.name = control.id, control.type, control.name.encode()
        query.minimum, query.maximum, query.step, query.default_value = control.minimum, control.maximum, 1, \
            control.default
        query.flags, query.elem_size, query.elems = 0, 4, 1

    def _s_ext_ctrls(self, fd: int, request: Any) -> None:
        for index in range(request.count):
            wanted = request.controls[index]
            control = next(control for control in self.controls if control.id == wanted.id)
            control.value = wanted.value

    def _g_ext_ctrls(self, fd: int, request: Any) -> None:
        for index in range(request.count):
            wanted = request.controls[index]
            wanted.value = next(control for control in self.controls if control.id == wanted.id).value

    def value(self, name: str) -> int:
        return next(control.value for control in self.controls if control.name == name)
