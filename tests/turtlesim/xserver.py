"""A real X server for the window tests: a private Xvfb, and what xwininfo and xwd say of it.

Each Xvfb gets a random display number from a wide range, not the lowest free one that every
server of two test runs side by side (and of other work) reaches for: a simulator's window test,
run beside another suite, once found its fresh Xvfb on :0 unreachable ("could not connect to
display :0"). It runs with -noreset: by default an X server resets whenever its last client
disconnects, and a client connecting meanwhile is refused ("could not connect to display"). The
tests' own probes (xwininfo, xwd, xdotool) connect and leave every few hundred milliseconds while
the program under test starts, so a loaded machine's slower resets made a window's program abort
now and then (measured: 17 of 300 connections refused beside xwininfo's, 0 with -noreset). It says
it is ready through -displayfd, logs to a file (not a pipe nobody reads, which a chatty server could
fill and stall on), and is stopped by its PID. Without Xvfb
(or xwininfo of x11-utils, xwd of x11-apps) the tests that need them skip and say which is missing;
scripts/install-gui-libs.sh --xvfb installs them.
"""

from __future__ import annotations

import os
import random
import re
import shutil
import signal
import struct
import subprocess
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import pytest


def require_x_tools() -> None:
    for tool, package in (("Xvfb", "xvfb"), ("xwininfo", "x11-utils"), ("xwd", "x11-apps")):
        if shutil.which(tool) is None:
            pytest.skip(f"{tool} is not installed (apt-get install {package}; scripts/install-gui-libs.sh --xvfb)")


@contextmanager
def xvfb(size: str = "800x600") -> Iterator[str]:
    """A running Xvfb of `size` pixels (24-bit colour); yields its DISPLAY (":N")."""
    require_x_tools()
    said = ""
    for _ in range(20):  # a number another server holds: that one refuses it, try another
        number = random.randrange(100, 50000)
        if os.path.exists(f"/tmp/.X{number}-lock"):
            continue
        with tempfile.TemporaryFile() as log:
            read, write = os.pipe()
            server = subprocess.Popen(["Xvfb", f":{number}", "-displayfd", str(write), "-screen", "0", f"{size}x24",
                                       "-nolisten", "tcp", "-noreset"],
                                      pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=log)
            os.close(write)
            try:
                with os.fdopen(read) as pipe:
                    ready = pipe.readline().strip()  # written once the server accepts clients
                if ready:
                    yield f":{ready}"
                    return
                server.wait(10)
                log.seek(0)
                said = log.read().decode(errors="replace")
            finally:
                _stop(server)
    raise RuntimeError(f"Xvfb did not start: {said}")


def _stop(server: subprocess.Popen[bytes]) -> None:
    if server.poll() is None:
        os.kill(server.pid, signal.SIGTERM)
        try:
            server.wait(10)
        except subprocess.TimeoutExpired:
            os.kill(server.pid, signal.SIGKILL)
            server.wait()


@dataclass(frozen=True)
class XWindow:
    id: str
    title: str
    width: int
    height: int
    viewable: bool


def find_window(display: str, title: str) -> XWindow | None:
    """The top-level window called `title` (as xwininfo sees it), or None while there is none; of
    several with that name (Qt's unmapped 1x1 leader window shares its program's title), a
    viewable one first."""
    windows = find_windows(display, title)
    return next((w for w in windows if w.viewable), windows[0] if windows else None)


def find_windows(display: str, title: str) -> list[XWindow]:
    env = dict(os.environ, DISPLAY=display)
    tree = subprocess.run(["xwininfo", "-root", "-tree"], env=env, capture_output=True, text=True, timeout=10).stdout
    found = []
    for match in re.finditer(r"^\s*(0x[0-9a-f]+) \"" + re.escape(title) + r"\"", tree, re.MULTILINE):
        info = subprocess.run(["xwininfo", "-id", match.group(1)], env=env, capture_output=True, text=True,
                              timeout=10).stdout
        width = int(re.search(r"Width: (\d+)", info).group(1))  # type: ignore[union-attr]
        height = int(re.search(r"Height: (\d+)", info).group(1))  # type: ignore[union-attr]
        found.append(XWindow(match.group(1), title, width, height, "Map State: IsViewable" in info))
    return found


def find_shown_window(display: str, title: str) -> XWindow | None:
    """The window called `title` once it is mapped and viewable: xwd cannot read a window that a
    program has named but not shown yet."""
    window = find_window(display, title)
    return window if window is not None and window.viewable else None


@dataclass(frozen=True)
class Screenshot:
    """An xwd dump of a window (ZPixmap, 24/32 bits per pixel, TrueColor)."""
    width: int
    height: int
    data: bytes
    bytes_per_line: int
    bytes_per_pixel: int
    little_endian: bool

    def rgb(self, x: int, y: int) -> tuple[int, int, int]:
        i = y * self.bytes_per_line + x * self.bytes_per_pixel
        pixel = int.from_bytes(self.data[i:i + self.bytes_per_pixel], "little" if self.little_endian else "big")
        return (pixel >> 16) & 0xFF, (pixel >> 8) & 0xFF, pixel & 0xFF

    def colours(self, x0: int, y0: int, x1: int, y1: int) -> set[tuple[int, int, int]]:
        return {self.rgb(x, y) for x in range(max(x0, 0), min(x1, self.width))
                for y in range(max(y0, 0), min(y1, self.height))}


def screenshot(display: str, window_id: str) -> Screenshot:
    """What the X server shows of a window (xwd), read as XWD's documented header says."""
    dump = subprocess.run(["xwd", "-silent", "-id", window_id], env=dict(os.environ, DISPLAY=display),
                          capture_output=True, timeout=20, check=True).stdout
    header = struct.unpack(">25I", dump[:100])
    header_size, pixmap_format, width, height = header[0], header[2], header[4], header[5]
    byte_order, bits_per_pixel, bytes_per_line, ncolors = header[7], header[11], header[12], header[19]
    assert pixmap_format == 2 and bits_per_pixel in (24, 32), header  # ZPixmap, true colour
    start = header_size + 12 * ncolors
    return Screenshot(width, height, dump[start:], bytes_per_line, bits_per_pixel // 8, byte_order == 0)
