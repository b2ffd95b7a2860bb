"""rqt: the rqt tools as plugins of one window, its layout remembered between runs.

    rqt [--perspective-file FILE] [--clear-config] [-s|--standalone PLUGIN] [--list-plugins]
        [__master:=URI] [__ip:=...]

The Plugins menu opens Node Graph, Plot, Console, Logger Level (and so on) as docks, as many
of each as wanted. The plugins, their docks and the window come back next time (the
perspective: <ROS_HOME>/kame/rqt_gui.json unless --perspective-file says). --standalone shows
one plugin alone and remembers nothing. Also `rosrun rqt_gui rqt_gui`; rqt_topic, rqt_publisher,
rqt_service_caller, rqt_reconfigure and rqt_image_view [TOPIC] are their plugins standalone,
as in ROS.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from kame import names
from kame.rqt.perspective import PLUGINS, PerspectiveError, dock_title, find_plugin, perspective_path


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rqt", description="The rqt tools in one window.")
    p.add_argument("--perspective-file", type=Path, help="the perspective to open and keep (JSON)")
    p.add_argument("--clear-config", action="store_true", help="start from an empty window (forget the perspective)")
    p.add_argument("-s", "--standalone", metavar="PLUGIN", help="show only this plugin, remembering nothing")
    p.add_argument("--list-plugins", action="store_true", help="list the plugins and exit")
    p.add_argument("--image-topic", help=argparse.SUPPRESS)  # rqt_image_view's TOPIC
    return p


def main(argv: Sequence[str] | None = None) -> int:
    ros = names.parse_args(sys.argv[1:] if argv is None else argv)
    args = parser().parse_args(ros.argv)
    if args.list_plugins:
        for info in PLUGINS:
            print(f"{info.rqt_name}  ({info.group} > {info.title})")
        return 0
    try:
        standalone = find_plugin(args.standalone) if args.standalone else None
    except PerspectiveError as exc:
        print(f"rqt: {exc}", file=sys.stderr)
        return 2
    try:
        from kame.qt_quit import quit_on_signals
        from kame.rqt.console_window import application
        from kame.rqt.gui_window import RqtWindow
    except ImportError as exc:
        print(f"rqt needs PySide6, grandalf and pyqtgraph (pip install 'kame[gui]'): {exc}", file=sys.stderr)
        return 1
    from kame.rqt.plugins import PluginContext
    from kame.rqt.ros_node import master_uri

    app = application("rqt")
    quit_on_signals(app)  # Ctrl-C closes the tool as its window does
    context = PluginContext(master_uri(ros.special), ros.special)
    if standalone is not None:
        window = RqtWindow(context, None)
        window.menuBar().hide()
        window.add_plugin(standalone.id, settings={"topic": args.image_topic} if args.image_topic else None)
        window.setWindowTitle(dock_title(standalone, 1))
    else:
        path = args.perspective_file or perspective_path(os.environ, Path.home())
        if args.clear_config and path.exists():
            path.unlink()
        window = RqtWindow(context, path)
        for problem in window.load_perspective():
            print(f"rqt: {problem}", file=sys.stderr)
    window.show()
    return int(app.exec())


def _standalone(plugin: str, argv: Sequence[str] | None) -> int:
    return main(["--standalone", plugin, *(sys.argv[1:] if argv is None else argv)])


def topic_main(argv: Sequence[str] | None = None) -> int:
    return _standalone("rqt_topic", argv)


def publisher_main(argv: Sequence[str] | None = None) -> int:
    return _standalone("rqt_publisher", argv)


def service_caller_main(argv: Sequence[str] | None = None) -> int:
    return _standalone("rqt_service_caller", argv)


def reconfigure_main(argv: Sequence[str] | None = None) -> int:
    return _standalone("rqt_reconfigure", argv)


def image_view_main(argv: Sequence[str] | None = None) -> int:
    """rqt_image_view [TOPIC]: the image topic to show at once."""
    args = list(sys.argv[1:] if argv is None else argv)
    topics = [a for a in args if a.startswith("/") and ":=" not in a]
    rest = [a for a in args if a not in topics]
    return _standalone("rqt_image_view", rest + (["--image-topic", topics[0]] if topics else []))


if __name__ == "__main__":
    sys.exit(main())
