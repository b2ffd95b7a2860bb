"""Paint turtlesim's window FRAMES times in this one process, a turtle drawing as it goes, and
print how many frames were painted and how many references to None the process lost.

    python -m tests.turtlesim.many_frames FRAMES

Run by tests/turtlesim/test_gui.py in a child, because the failure it looks for is the whole
interpreter aborting (PySide6-Essentials 6.12.0 on Python 3.10/3.11: 'Fatal Python error:
none_dealloc' after a few thousand Qt calls).
"""

from __future__ import annotations

import random
import sys

from kame.msg.catalog import SHARE_DIR
from kame.turtlesim import World, gui


def main() -> int:
    frames = int(sys.argv[1])
    app = gui.application()
    world = World(rng=random.Random(1))
    world.reset()
    world.spawn("turtle2", 2.0, 2.0, 0.0)
    window = gui.TurtleWindow(world.snapshot(), "TurtleSim", gui.load_turtle_images(SHARE_DIR / "turtlesim" / "images"))
    window.show()
    # on a real X server a window paints only once it is exposed, which a loaded machine can leave
    # for later than one processEvents(): repaint() then painted nothing for the whole loop
    from PySide6.QtTest import QTest

    if not QTest.qWaitForWindowExposed(window, 30_000):
        print("the window was never exposed", flush=True)
        return 1
    app.processEvents()
    painted_before = window.frames_painted
    none_before = sys.getrefcount(None)
    for n in range(frames):
        if n % 50 == 0:  # drive in circles, drawing, so every frame has something new
            world.command("turtle1", 2.0, 0.0, 1.5)
            world.command("turtle2", 1.0, 0.0, -1.0)
        world.step()
        window.show_snapshot(world.snapshot())
        window.repaint()  # paints now: one paintEvent per frame
    lost = none_before - sys.getrefcount(None)
    print(f"painted {window.frames_painted - painted_before} lost {lost}", flush=True)
    window.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
