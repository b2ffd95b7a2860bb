"""Renders every case of render_cases in rviz's window (top-down, 50 pixels a metre), reads the
frame buffer back and prints one line per case: its name, the colour at its probe point's pixel
(the closest to the expected colour within 3 pixels, as lines and points are thin) and the
colour far from all geometry. Run where Qt has OpenGL (a private Xvfb in the tests).

    python -m tests.rviz.render_child [SCREENSHOT.png]
"""

from __future__ import annotations

import sys

import numpy as np
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

from kame.rviz import config
from kame.rviz.camera import TOP_DOWN, Camera
from kame.rviz.window import RvizWindow
from tests.rviz.render_cases import CASES, Frames


def main() -> int:
    app = QApplication(["rviz"])
    settings = config.Config(camera=Camera(kind=TOP_DOWN, scale=50.0), displays=[])
    settings.background = (0.2, 0.2, 0.2, 1.0)  # 51, 51, 51: no case draws it
    window = RvizWindow(settings, None)
    window.timer.stop()  # the test draws each frame itself
    window.resize(900, 500)
    window.show()
    if not QTest.qWaitForWindowExposed(window, 10_000):
        print("never exposed", flush=True)
        return 1
    print(f"platform {app.platformName()}", flush=True)
    view = window.view
    for case in CASES:
        display, messages = case.make()
        display.receive(messages, 0.0)
        settings.displays = [display]
        window.draw(0.0, Frames())
        image = view.grabFramebuffer()
        ratio = image.width() / max(1, view.width())
        x, y = (view.camera.project([case.probe], view.width(), view.height())[0] + case.offset) * ratio
        best = None
        for dx in range(-3, 4):
            for dy in range(-3, 4):
                rgb = image.pixelColor(round(float(x)) + dx, round(float(y)) + dy).getRgb()[:3]
                distance = sum(abs(a - b) for a, b in zip(rgb, case.color, strict=True))
                if best is None or distance < best[0]:
                    best = (distance, rgb)
        empty = image.pixelColor(5, 5).getRgb()[:3]
        assert best is not None
        print(f"case {case.name.replace(' ', '_')} {display.status.level} {','.join(map(str, best[1]))} "
              f"{','.join(map(str, empty))}", flush=True)
    # Measure picks what is drawn: on the cube (0.5 m, centred on the ground) its top, beside it the ground
    cube = next(case for case in CASES if case.name == "Marker cube")
    display, messages = cube.make()
    display.receive(messages, 0.0)
    settings.displays = [display]
    window.draw(0.0, Frames())
    for name, (x, y) in (("on", cube.probe[:2]), ("beside", (cube.probe[0] + 1.0, cube.probe[1]))):
        px, py = view.camera.project([[x, y, 0.0]], view.width(), view.height())[0]
        picked = view.pick(float(px), float(py))
        assert picked is not None
        print(f"pick {name} {','.join(f'{v:.3f}' for v in picked)}", flush=True)
    # Select marks what it selected over everything: the cube's centre, inside the cube
    px, py = view.camera.project([list(cube.probe)], view.width(), view.height())[0]
    window._select((float(px), float(py)), (float(px), float(py)))
    image = view.grabFramebuffer()
    ratio = image.width() / max(1, view.width())
    marked = image.pixelColor(round(float(px) * ratio), round(float(py) * ratio)).getRgb()[:3]
    print(f"selected {len(window.selection.selected)} {','.join(map(str, marked))}", flush=True)
    if len(sys.argv) > 1:
        settings.displays = [case.make()[0] for case in CASES]
        for case, display in zip(CASES, settings.displays, strict=True):
            display.receive(case.make()[1], 0.0)
        window.draw(0.0, Frames())
        view.grabFramebuffer().save(sys.argv[1])
    window.close()
    return 0


if __name__ == "__main__":
    np.seterr(all="ignore")
    sys.exit(main())
