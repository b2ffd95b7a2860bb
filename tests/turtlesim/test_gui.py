"""turtlesim's window, offscreen: a screenshot of the widget, checked pixel by pixel; and the
node opening its window (no 'headless' line) when Qt can."""

from __future__ import annotations

import os
import random
from pathlib import Path

import pytest

from kame.turtlesim import World

pytest.importorskip("PySide6.QtWidgets")
if not os.environ.get("QT_QPA_PLATFORM"):
    os.environ["QT_QPA_PLATFORM"] = "offscreen"  # before Qt starts: no display in the tests

from PySide6.QtGui import QImage

from kame.turtlesim import gui


def rgb(image: QImage, x: int, y: int) -> tuple[int, int, int]:
    c = image.pixelColor(x, y)
    return c.red(), c.green(), c.blue()


def test_screenshot_shows_background_pen_line_and_turtle(tmp_path: Path) -> None:
    gui.application()
    world = World(rng=random.Random(3))
    world.reset()
    world.set_pen("turtle1", 255, 0, 0, 5, False)
    world.command("turtle1", 2.0, 0.0, 0.0)
    for _ in range(40):  # 1.28 m to the right, drawing
        world.step()
    window = gui.TurtleWindow(world.snapshot(), "TurtleSim")
    window.show()
    shot = window.grab().toImage()
    shot.save(str(tmp_path / "turtlesim.png"))
    assert window.windowTitle() == "TurtleSim"
    assert (shot.width(), shot.height()) == (500, 500)
    assert rgb(shot, 5, 5) == (69, 86, 255)  # background
    assert rgb(shot, 490, 490) == (69, 86, 255)
    assert rgb(shot, 265, 250) == (255, 0, 0)  # the pen line, 5 px wide, left behind the turtle
    assert rgb(shot, 265, 247) == (255, 0, 0) and rgb(shot, 265, 244) == (69, 86, 255)
    turtle_x = round(world.turtle("turtle1").pose.x * 45)
    shell = gui.PALETTE[world.turtle("turtle1").image]
    colours = {rgb(shot, x, y) for x in range(turtle_x - 20, turtle_x + 21) for y in range(230, 271)}
    from PySide6.QtGui import QColor

    wanted = {(QColor(c).red(), QColor(c).green(), QColor(c).blue()) for c in shell}
    assert wanted & colours, "the turtle's drawing is on the screenshot"
    # render() paints the same frame
    assert rgb(gui.render(world.snapshot()), 265, 250) == (255, 0, 0)
    window.close()


def test_the_node_opens_a_window_when_qt_can(tmp_path: Path) -> None:
    from tests.turtlesim.sim import master

    with master(tmp_path) as live:
        env = dict(live.env, QT_QPA_PLATFORM="offscreen")
        node = live.start("turtlesim", "turtlesim_node", env=env, wait="Spawning turtle [turtle1]")
        assert live.pose()["x"] == pytest.approx(5.544444561004639)
        out = "".join(node.out)
        assert "headless" not in out and "without a window" not in out
        assert node.popen.poll() is None
        # Ctrl-C ends the window's loop quietly (it used to raise into a Qt slot: a traceback)
        out, err = node.stop()
        assert node.popen.returncode == 0
        assert "Traceback" not in out + err, err
