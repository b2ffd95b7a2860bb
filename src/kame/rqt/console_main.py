"""rqt_console: the messages of every node (/rosout_agg) in a filterable table.

    rqt_console [--capacity N] [--topic /rosout_agg] [__master:=URI] [__ip:=...]

The tool runs as node /rqt_console_<pid>, and waits for the master when it is not up yet.
Messages are kept up to the capacity (20,000 unless set; the oldest go first).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from kame import names
from kame.rqt.console_model import DEFAULT_CAPACITY, LogView


def main(argv: Sequence[str] | None = None) -> int:
    ros = names.parse_args(sys.argv[1:] if argv is None else argv)
    parser = argparse.ArgumentParser(prog="rqt_console", description="Show the ROS log messages.")
    parser.add_argument("--capacity", type=int, default=DEFAULT_CAPACITY, help="messages kept (oldest dropped)")
    parser.add_argument("--topic", default="/rosout_agg", help="the rosgraph_msgs/Log topic to show")
    args = parser.parse_args(ros.argv)
    if args.capacity < 1:
        parser.error("--capacity must be at least 1")
    try:
        from kame.qt_quit import quit_on_signals
        from kame.rqt.console_window import ConsoleWindow, application
    except ImportError as exc:
        print(f"rqt_console needs PySide6 (pip install 'kame[gui]'): {exc}", file=sys.stderr)
        return 1
    from kame.rqt.ros_node import start_node

    app = application("rqt_console")
    quit_on_signals(app)  # Ctrl-C closes the tool as its window does
    window = ConsoleWindow(LogView(args.capacity))
    node = start_node("console", ros.special)
    try:
        window.listen(node, args.topic)  # waits for the master first when there is none yet
        window.show()
        return int(app.exec())
    finally:
        window.stop_waiting()
        node.shutdown("rqt_console exiting")


if __name__ == "__main__":
    sys.exit(main())
