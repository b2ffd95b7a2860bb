"""`rviz [-d FILE.rviz] [-f FIXED_FRAME] [--stats]` (also `rosrun rviz rviz`): the window on a node
named /rviz_<pid> (rviz's anonymous name) or its `__name:=` (a launch file's name="rviz"), with
ROS remappings, __ns and __master honoured; a -d file that is not there is said so and the
default layout opens, as rviz does; --stats prints how well the window keeps up
(kame.rviz.stats) each second. Without PySide6/PyOpenGL it says which extra to install."""

from __future__ import annotations

import argparse
import gc
import os
import sys
import time
from collections.abc import Sequence

from kame import names
from kame.rviz import config as rviz_config


def startup_config(path: str, fixed_frame: str) -> tuple[rviz_config.Config, str]:
    """The layout rviz opens with and its file: `path`'s, or rviz's default (a grid) without
    one. A `path` that is not there is said so and the default opens, as rviz's
    loadDisplayConfig does. OSError or ValueError for a file that cannot be read as one."""
    if path and not os.path.isfile(path):
        from kame.cli._console import console

        console("ERROR", f"{path} does not exist!")
        path = ""
    config = rviz_config.load(path) if path else rviz_config.Config()
    if not path:
        config.displays = [rviz_config.DISPLAY_CLASSES["rviz/Grid"]()]
    if fixed_frame:
        config.fixed_frame = fixed_frame
    return config, path


def main(argv: Sequence[str] | None = None) -> int:
    ros = names.parse_args(sys.argv[1:] if argv is None else argv)
    parser = argparse.ArgumentParser(prog="rviz", description="3-D visualisation of ROS topics and tf")
    parser.add_argument("-d", "--display-config", default="", help="a .rviz file to load")
    parser.add_argument("-f", "--fixed-frame", default="", help="the fixed frame (overrides the file's)")
    parser.add_argument("--stats", action="store_true",
                        help="print each second the frames drawn and the longest the window was busy")
    options = parser.parse_args(ros.argv)
    try:
        from PySide6.QtWidgets import QApplication

        from kame.qt_quit import quit_on_signals
        from kame.rviz.window import RvizWindow
    except ImportError as exc:
        print(f"rviz needs the gui extra (pip install 'kame[gui]'): {exc}", file=sys.stderr)
        return 1
    from kame.node.config import node_config
    from kame.node.node import Node
    from kame.rviz.source import RvizSource

    try:
        config, options.display_config = startup_config(options.display_config, options.fixed_frame)
    except (OSError, ValueError) as exc:
        print(f"rviz: cannot load {options.display_config}: {exc}", file=sys.stderr)
        return 1
    # X11 Qt holds a window's update request 5 ms for more to join it: the view's frames are
    # paced already (kame.rviz.pacing), and a message would wait those 5 ms more for its pixels
    os.environ.setdefault("QT_QPA_UPDATE_IDLE_TIME", "0")
    app = QApplication.instance() or QApplication(["rviz"])
    quit_on_signals(app)
    node = Node(node_config(f"rviz_{os.getpid()}", ros.special, os.environ, ros.remappings))
    source: RvizSource | None = None
    try:
        source = RvizSource(node, lambda: None)  # the window hooks its frame pacer in
        window = RvizWindow(config, source, options.display_config)
        window.resize(*rviz_config.window_size(config))
        window.show()
        if options.stats:
            from PySide6.QtCore import QTimer

            reporter = QTimer(window)
            reporter.timeout.connect(lambda: print(window.stats.report(time.monotonic()), flush=True))
            reporter.start(1000)
        # what is alive now (Qt, numpy, the message classes) lives as long as the window: kept
        # out of the collector's full passes, which otherwise walk it all while a 2,000-marker
        # array is decoded (40 ms more of a message's latency, every third array or so)
        gc.collect()  # garbage first: frozen, it would never be freed
        gc.freeze()
        return int(app.exec())
    finally:
        if source is not None:
            source.close()
        node.shutdown("rviz closed")
