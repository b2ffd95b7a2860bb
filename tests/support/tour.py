"""The screenshot tour: GUI tests save what the X server shows of a course's window as a PNG in
a folder the test run keeps ($KAME_TOUR_DIR, else build/tour in the repository), so that each
change to a window can be looked at, and docs/images refreshed from it.

A shot is taken once the window is mapped and what it shows passes the caller's check (the
turtle's trail drawn, a curve plotted): X sends no event for that, so the window is read
again every SHOT_PERIOD until it does."""

from __future__ import annotations

import os
import struct
import time
import zlib
from collections.abc import Callable
from pathlib import Path

from tests.support import REPO, Proc
from tests.turtlesim.xserver import Screenshot, find_shown_window, screenshot

SHOT_PERIOD = 0.3  # seconds between two reads of a window that does not show what is wanted yet


def tour_dir() -> Path:
    folder = Path(os.environ.get("KAME_TOUR_DIR") or REPO / "build" / "tour")
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def png(shot: Screenshot) -> bytes:
    """The screenshot as an RGB PNG (zlib, no filter: no imaging library needed)."""
    rows = []
    for y in range(shot.height):
        line = shot.data[y * shot.bytes_per_line:y * shot.bytes_per_line + shot.width * shot.bytes_per_pixel]
        rgb = bytearray(shot.width * 3)
        step = shot.bytes_per_pixel
        red, green, blue = (2, 1, 0) if shot.little_endian else (step - 3, step - 2, step - 1)
        rgb[0::3], rgb[1::3], rgb[2::3] = line[red::step], line[green::step], line[blue::step]
        rows.append(b"\0" + bytes(rgb))

    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    header = struct.pack(">IIBBBBB", shot.width, shot.height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(b"".join(rows), 6))
            + chunk(b"IEND", b""))


def shoot(display: str, title: str, name: str, ready: Callable[[Screenshot], bool] = lambda shot: True,
          timeout: float = 60.0, program: Proc | None = None) -> Screenshot:
    """Waits for the window called `title` to be mapped and to pass `ready`, and saves it as
    `name`.png in the tour folder. A failure tells what `program` (the window's) said last."""
    deadline = time.monotonic() + timeout
    shot: Screenshot | None = None
    while time.monotonic() < deadline:
        window = find_shown_window(display, title)
        if window is not None:
            shot = screenshot(display, window.id)
            if ready(shot):
                (tour_dir() / f"{name}.png").write_bytes(png(shot))
                return shot
        time.sleep(SHOT_PERIOD)
    if shot is not None:  # what it showed instead, to look at
        (tour_dir() / f"{name}-not-ready.png").write_bytes(png(shot))
    said = "" if program is None else (f"; the program ({program.popen.poll()=}) said last:\n"
                                       + "".join(program.out[-10:] + program.err[-20:]))
    raise AssertionError(f"{title!r} never showed what {name} should show"
                         + (f" (its last shot: {tour_dir() / name}-not-ready.png)" if shot is not None
                            else " (never mapped)") + said)


def count(shot: Screenshot, colour: tuple[int, int, int], step: int = 2) -> int:
    """About how many of the shot's pixels are `colour` (every `step`-th row and column)."""
    return sum(1 for y in range(0, shot.height, step) for x in range(0, shot.width, step) if shot.rgb(x, y) == colour)


def dark(shot: Screenshot, top: int = 0, bottom: int | None = None, left: int = 0, step: int = 3) -> int:
    """About how many pixels below row `top`, above `bottom` and right of column `left` are near
    black (text, lines): more once a window has drawn its content there."""
    end = shot.height if bottom is None else min(bottom, shot.height)
    return sum(1 for y in range(top, end, step) for x in range(left, shot.width, step) if sum(shot.rgb(x, y)) < 150)
