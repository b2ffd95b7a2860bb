"""The rqt window in a process of its own, on whatever display its environment gives Qt (the
tests run it offscreen and on a private Xvfb): it docks Node Graph and Console, prints "shown",
waits for a line on stdin (the test looks at the X server meanwhile), closes (saving the
perspective), opens the window again from the perspective and prints what came back.

    python -m tests.rqt.rqt_window_child MASTER_URI PERSPECTIVE_FILE
"""

from __future__ import annotations

import sys
from pathlib import Path

from PySide6.QtCore import QEventLoop, QTimer
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

from kame.rqt.graph_model import Kind
from kame.rqt.graph_window import GraphWindow
from kame.rqt.gui_window import RqtWindow
from kame.rqt.plugins import PluginContext


def main() -> int:
    master_uri, path = sys.argv[1], Path(sys.argv[2])
    app = QApplication(["rqt"])
    context = PluginContext(master_uri)
    window = RqtWindow(context, path)
    window.add_plugin("rqt_graph")
    window.add_plugin("rqt_console")
    window.resize(700, 500)
    window.show()
    if not QTest.qWaitForWindowExposed(window, 10_000):
        print("never exposed", flush=True)
        return 1
    graph = window.docks["rqt_graph#1"].handle.widget
    assert isinstance(graph, GraphWindow)
    if graph.scene_model is None:  # its first refresh is still on its way
        loop = QEventLoop()
        graph.refreshed.connect(loop.quit)
        QTimer.singleShot(10_000, loop.quit)
        loop.exec()
    nodes = graph.scene_model.names(Kind.NODE) if graph.scene_model is not None else []
    print(f"shown {app.platformName()} {window.width()}x{window.height()} graph nodes {','.join(nodes)}", flush=True)
    sys.stdin.readline()
    window.close()
    again = RqtWindow(context, path)
    problems = again.load_perspective()
    again.show()
    QTest.qWaitForWindowExposed(again, 10_000)
    print(f"again {again.width()}x{again.height()} docks {','.join(sorted(again.docks))} problems {problems}",
          flush=True)
    again.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
