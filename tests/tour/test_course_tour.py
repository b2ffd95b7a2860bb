"""The courses' windows under Xvfb, each saved to the tour folder (tests/support/tour.py) once it
shows what the course shows: turtlesim drawing squares, rqt_graph on that graph, rqt_plot of
the turtle's pose, rqt_console with draw_square's messages, the rqt window with Node Graph, Plot
and Console docked, and rviz on the tf2 demo with the tutorial's turtle_rviz.rviz. (rviz's
view_robot and view_navigation and stageros are shot by their own tests.) One X server, one
master and one turtlesim serve every shot of a test."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from kame.rqt.perspective import DockedPlugin, Perspective, dumps
from tests.support import Proc, free_port, ros_env, wait_for_master
from tests.support.tour import count, dark, shoot
from tests.turtlesim.sim import BIN
from tests.turtlesim.xserver import Screenshot

pytest.importorskip("PySide6")

TRAIL = (179, 184, 255)  # turtlesim's pen
CURVE = (31, 119, 180)  # rqt_plot's first curve


class Desktop:
    """roscore and the programs started on one Xvfb display; each stopped by its PID."""

    def __init__(self, home: Path, display: str) -> None:
        port = free_port()
        self.uri = f"http://127.0.0.1:{port}/"
        self.env = dict(ros_env(home, self.uri), DISPLAY=display)
        self.display = display
        self.home = home
        self.procs = [Proc([str(BIN / "roscore"), "-p", str(port)], self.env, cwd=home)]
        wait_for_master(self.uri, proc=self.procs[0], timeout=30)

    def start(self, program: str, *args: str) -> Proc:
        proc = Proc([str(BIN / program), *args], self.env, cwd=self.home)
        self.procs.append(proc)
        return proc

    def stop(self) -> None:
        for proc in reversed(self.procs):
            proc.stop()


@pytest.fixture
def desktop(tmp_path: Path) -> Iterator[Desktop]:
    from tests.turtlesim.xserver import xvfb

    with xvfb("1600x1000") as display:
        graph = Desktop(tmp_path, display)
        try:
            yield graph
        finally:
            graph.stop()


def test_the_turtlesim_lessons_windows(desktop: Desktop) -> None:
    desktop.start("rosrun", "turtlesim", "turtlesim_node")
    desktop.start("rosrun", "turtlesim", "draw_square")
    shoot(desktop.display, "TurtleSim", "turtlesim", lambda shot: count(shot, TRAIL) > 120)  # a side or two

    graph = desktop.start("rqt_graph")
    shoot(desktop.display, "rqt_graph", "rqt_graph", lambda shot: dark(shot, top=100) > 300)  # below its controls
    graph.stop()

    plot = desktop.start("rqt_plot", "/turtle1/pose/x", "/turtle1/pose/y")
    shoot(desktop.display, "rqt_plot", "rqt_plot", lambda shot: count(shot, CURVE) > 100)
    plot.stop()

    console = desktop.start("rqt_console")
    shoot(desktop.display, "rqt_console", "rqt_console", lambda shot: dark(shot, bottom=300) > 250)  # some rows
    console.stop()

    perspective = desktop.home / "three_docks.json"
    perspective.write_text(dumps(Perspective((
        DockedPlugin("rqt_graph", 1, {}), DockedPlugin("rqt_plot", 1, {"series": ["/turtle1/pose/x"]}),
        DockedPlugin("rqt_console", 1, {})), "", "")))
    desktop.start("rqt", "--perspective-file", str(perspective))
    # at 1200x800 Plot docks left, Node Graph right above Console: a curve, and rows in the Console
    shoot(desktop.display, "Default - rqt", "rqt_three_docks",
          lambda shot: count(shot, CURVE) > 50 and dark(shot, top=460, bottom=650, left=shot.width // 2 + 20) > 60)


def test_the_tf_tutorials_rviz_step(desktop: Desktop) -> None:
    pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
    desktop.start("roslaunch", "turtle_tf2", "turtle_tf2_demo.launch")
    found = desktop.start("rospack", "find", "turtle_tf2")
    found.popen.wait(30)
    config = Path(found.stop()[0].strip()) / "rviz" / "turtle_rviz.rviz"
    desktop.start("rosrun", "rviz", "rviz", "-d", str(config))

    def frames_drawn(shot: Screenshot) -> bool:  # the three frames' red x axes (every other column)
        return sum(1 for y in range(shot.height) for x in range(0, shot.width, 2)
                   if (lambda r, g, b: r > 180 and g < 70 and b < 70)(*shot.rgb(x, y))) > 40

    shoot(desktop.display, "turtle_rviz.rviz - RViz", "rviz_turtle_tf2", frames_drawn, timeout=90)
