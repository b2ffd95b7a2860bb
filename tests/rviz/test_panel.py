"""rviz's Displays panel as a user works it, offscreen on a live master: the Global Options'
fixed-frame choice lists the frames tf knows, a display's option and the global options edited
in the tree reach the displays, the view and the frame timer, Add > a display type adds one that
subscribes, and a display's warning shows in its Status row."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

from PySide6.QtCore import Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QLineEdit, QPushButton, QTreeWidgetItem

from geometry_msgs.msg import TransformStamped
from kame.node.node import Node, NodeConfig
from kame.rviz import config, displays
from kame.rviz.source import RvizSource
from kame.rviz.window import STATUS_COLOURS, RvizWindow
from tests.tf.graph import Graph

TREE = (("map", "odom", 1.0), ("odom", "base_link", 0.5), ("base_link", "laser", 0.2))


def _row(parent: QTreeWidgetItem, key: str) -> QTreeWidgetItem:
    rows = [parent.child(i) for i in range(parent.childCount())]
    return next(row for row in rows if row.text(0) == key)


def _type_into(qtbot: Any, window: RvizWindow, row: QTreeWidgetItem, text: str) -> None:
    """What a double click on the row's value, typing `text` and Return do: the tree's editor
    commits it to the item (the delegate does so on the event loop's next turn)."""
    tree = window.tree
    tree.editItem(row, 1)
    editor = tree.indexWidget(tree.indexFromItem(row, 1))
    assert isinstance(editor, QLineEdit), editor
    editor.selectAll()
    QTest.keyClicks(editor, text)
    QTest.keyClick(editor, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: row.text(1) == text, timeout=10_000)


def test_the_displays_panel_as_a_user_works_it(tmp_path: Path, qtbot: Any) -> None:
    graph = Graph(tmp_path)
    rviz = Node(NodeConfig("/rviz_panel_test", graph.uri, "127.0.0.1", "127.0.0.1"))
    source = RvizSource(rviz, lambda: None)
    try:
        for parent, child, x in TREE:
            transform = TransformStamped()
            transform.header.frame_id, transform.child_frame_id = parent, child
            transform.transform.translation.x = x
            transform.transform.rotation.w = 1.0
            assert source.buffer.set_transform_static(transform, "test")
        grid = displays.Grid(options={"Reference Frame": "map"})
        window = RvizWindow(config.Config(fixed_frame="map", displays=[grid]), source)
        qtbot.addWidget(window)
        window.timer.stop()  # the test takes each turn of the frame timer itself
        window.resize(900, 600)
        window.show()
        window.frame()

        # the fixed frame is chosen from tf's frames
        choice = window.fixed_frames
        assert [choice.itemText(i) for i in range(choice.count())] == ["base_link", "laser", "map", "odom"]
        assert choice.currentText() == "map"
        assert window.view.scene.batches[0].vertices[:, 0].min() == pytest.approx(-5.0)
        choice.setCurrentIndex(choice.findText("odom"))
        assert window.config.fixed_frame == "odom"
        window.frame()
        assert window.view.scene.batches[0].vertices[:, 0].min() == pytest.approx(-5.0 - 1.0)  # map is 1 m behind odom

        # a display's options, typed into its rows
        grid_item = window.tree.topLevelItem(1)
        assert (grid_item.text(0), grid_item.text(1)) == ("Grid", "rviz/Grid")
        _type_into(qtbot, window, _row(grid_item, "Color"), "0; 255; 0")
        _type_into(qtbot, window, _row(grid_item, "Plane Cell Count"), "4")
        _type_into(qtbot, window, _row(grid_item, "Cell Size"), "0.5")
        assert (grid.options["Color"], grid.options["Plane Cell Count"], grid.options["Cell Size"]) == \
            ("0; 255; 0", 4, 0.5)  # a number typed over a whole one may have a fraction
        window.frame()
        lines = window.view.scene.batches[0]
        assert tuple(lines.float_colors()[0][:3]) == pytest.approx((0.0, 1.0, 0.0))
        assert len(lines.vertices) == 2 * 2 * 5  # 4 cells a side: 5 lines each way, 2 points each
        assert lines.vertices[:, 0].min() == pytest.approx(-1.0 - 1.0)  # 2 m wide, about map's origin

        # the global options
        options = window.tree.topLevelItem(0)
        _type_into(qtbot, window, _row(options, "Background Color"), "10; 20; 30")
        assert window.view.background[:3] == pytest.approx((10 / 255, 20 / 255, 30 / 255))
        assert window.config.background[:3] == pytest.approx((10 / 255, 20 / 255, 30 / 255))
        _type_into(qtbot, window, _row(options, "Frame Rate"), "10")
        assert window.config.frame_rate == 10 and window.timer.interval() == 100

        # Add > rviz/LaserScan: a new display in the tree, subscribed to its topic
        add = next(button for button in window.findChildren(QPushButton) if button.text() == "Add")
        next(action for action in add.menu().actions() if action.text() == "rviz/LaserScan").trigger()
        scan = window.config.displays[-1]
        assert isinstance(scan, displays.LaserScan)
        added = window.tree.topLevelItem(window.tree.topLevelItemCount() - 1)
        assert (added.text(0), added.text(1)) == ("LaserScan", "rviz/LaserScan")
        assert _row(added, "Topic").text(1) == "/scan" and "/scan" in source.watched()

        # nothing has come on /scan: the display says so in its Status row, in rviz's warning colour
        window.frame()
        status = _row(added, "Status")
        assert status.text(1) == "Warn: no messages received on /scan"
        assert status.foreground(0).color().getRgb()[:3] == STATUS_COLOURS["Warn"]
        assert added.foreground(0).color().getRgb()[:3] == STATUS_COLOURS["Warn"]
        assert _row(window.tree.topLevelItem(1), "Status").text(1) == "Ok"  # the tree was built again
        window.close()
    finally:
        source.close()
        rviz.shutdown("test over")
        graph.stop()
