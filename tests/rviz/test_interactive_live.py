"""rviz's InteractiveMarkers display on a live server: the tutorial's simple_marker (rosrun) on
its update namespace, its box control read back from the frame buffer under Xvfb, and a drag
of its move_x arrow with the Interact tool arriving at the server's callback."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import pytest

from tests.support import REPO, Proc
from tests.tf.graph import Graph
from tests.turtlesim.sim import BIN

pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

RVIZ_FILE = """\
Visualization Manager:
  Displays:
    - Class: rviz/InteractiveMarkers
      Enabled: true
      Name: InteractiveMarkers
      Update Topic: /simple_marker/update
      Show Descriptions: true
  Global Options:
    Fixed Frame: base_link
  Views:
    Current:
      Class: rviz/TopDownOrtho
      Scale: 100
"""


def test_simple_markers_box_is_drawn_and_dragged(tmp_path: Path) -> None:
    from tests.turtlesim.xserver import xvfb

    graph = Graph(tmp_path)
    try:
        rviz_file = tmp_path / "markers.rviz"
        rviz_file.write_text(RVIZ_FILE)
        server = graph.start([str(BIN / "rosrun"), "interactive_marker_tutorials", "simple_marker.py"])
        # tf must know the fixed frame (rviz's status says so otherwise)
        graph.start([str(BIN / "rosrun"), "tf2_ros", "static_transform_publisher", "0", "0", "0", "0", "0", "0",
                     "world", "base_link"])
        with xvfb() as display:
            env = {k: v for k, v in graph.env.items() if k not in ("WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
            rviz = Proc([sys.executable, "-m", "tests.rviz.live_child", graph.uri, str(rviz_file),
                         "--colour", "0,128,128",
                         "--drag", "0.8,0,1.3,0.3"], dict(env, DISPLAY=display), cwd=REPO)
            graph.procs.append(rviz)
            deadline, line = time.monotonic() + 90, ""
            while time.monotonic() < deadline:
                lines = [text for text in list(rviz.out) if text.startswith("frames ")]
                line = lines[-1] if lines else ""
                if "InteractiveMarkers:Ok colour" in line and int(line.split()[-1]) > 200:
                    break
                time.sleep(0.1)
            # the 0.45 m box at 100 px/m: about 45 x 45 pixels of its teal
            assert "InteractiveMarkers:Ok colour" in line and int(line.split()[-1]) > 200, (
                line, "".join(rviz.err)[-2000:])
            # the +x arrow grabbed at 0.8 m and dragged 0.5 m along x (and 0.3 m across, which
            # MOVE_AXIS ignores): the tutorial's callback prints where the marker is now
            server.wait_line("my_marker is now at 0.5", timeout=30)
    finally:
        graph.stop()
