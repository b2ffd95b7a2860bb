"""rviz's window (offscreen: no drawing needed) repaints only when the scene changed: a still
scene, every display reusing its cached batches, is not drawn again at the frame rate."""

from __future__ import annotations

from typing import Any

import pytest

pytest.importorskip("OpenGL", reason="rviz's window needs PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

from geometry_msgs.msg import PointStamped
from kame.rviz import config, displays
from tests.rviz.test_model import TREE, TreeOf


def test_a_still_scene_is_not_repainted(qtbot: Any) -> None:
    from kame.rviz.window import RvizWindow

    point = displays.PointStamped()
    window = RvizWindow(config.Config(fixed_frame="map", displays=[displays.Grid(), point]), None)
    qtbot.addWidget(window)
    window.timer.stop()
    clicked = PointStamped()
    clicked.header.frame_id = "odom"
    point.receive([clicked], 0.0)
    window.draw(0.0, TREE)
    shown = window.view.scene
    assert len(shown.batches) == 2
    window.draw(0.1, TREE)
    assert window.view.scene is shown  # the same batches: nothing to repaint
    window.draw(0.2, TreeOf("map", {"odom": ("map", (5.0, 0.0, 0.0))}))  # odom moved: the point with it
    assert window.view.scene is not shown and window.view.scene.batches[0] is shown.batches[0]
