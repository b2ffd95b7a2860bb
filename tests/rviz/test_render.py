"""rviz's window draws each display where it belongs: every case of render_cases rendered with
OpenGL (Mesa's software renderer on a private Xvfb), the frame buffer read back, the probe
point's pixel of the case's colour and the background elsewhere. Qt's offscreen platform has no
OpenGL context, so the window is tested on Xvfb only."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.rviz.render_cases import CASES
from tests.support import REPO

pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

BACKGROUND = (51, 51, 51)
TOLERANCE = 40  # summed over r, g, b: blending and Mesa's rounding at edges


def test_every_display_colours_its_place_in_the_frame_buffer(tmp_path: Path) -> None:
    from tests.turtlesim.xserver import xvfb

    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    screenshot = tmp_path / "all.png"
    with xvfb() as display:
        done = subprocess.run([sys.executable, "-m", "tests.rviz.render_child", str(screenshot)],
                              env=dict(env, DISPLAY=display), cwd=REPO, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "platform xcb" in done.stdout
    rendered = {}
    for line in done.stdout.splitlines():
        if line.startswith("case "):
            _, name, status, probe, empty = line.split()
            rendered[name] = (status, tuple(map(int, probe.split(","))), tuple(map(int, empty.split(","))))
    assert sorted(rendered) == sorted(case.name.replace(" ", "_") for case in CASES)
    for case in CASES:
        status, probe, empty = rendered[case.name.replace(" ", "_")]
        assert status == "Ok", case.name
        assert sum(abs(a - b) for a, b in zip(probe, case.color, strict=True)) <= TOLERANCE, (case.name, probe)
        assert empty == BACKGROUND, (case.name, empty)
    assert screenshot.stat().st_size > 0
    picks = {line.split()[1]: [float(v) for v in line.split()[2].split(",")]
             for line in done.stdout.splitlines() if line.startswith("pick ")}
    assert picks["on"] == pytest.approx([1.0, -2.0, 0.25], abs=0.03)  # the cube's top, read from the depth buffer
    assert picks["beside"] == pytest.approx([2.0, -2.0, 0.0], abs=0.03)
    selected = next(line.split() for line in done.stdout.splitlines() if line.startswith("selected "))
    marked = tuple(map(int, selected[2].split(",")))
    assert selected[1] == "1" and sum(abs(a - b) for a, b in zip(marked, (255, 89, 255), strict=True)) <= TOLERANCE
