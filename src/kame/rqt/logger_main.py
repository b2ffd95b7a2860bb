"""rqt_logger_level: see and set the logger levels of running nodes.

    rqt_logger_level [__master:=URI]

Lists the nodes offering get_loggers/set_logger_level (roscpp's services; rospy and kame nodes
offer them too), a node's loggers, and sets the chosen level.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from kame import names


def main(argv: Sequence[str] | None = None) -> int:
    ros = names.parse_args(sys.argv[1:] if argv is None else argv)
    if any(arg in ("-h", "--help") for arg in ros.argv):
        print(__doc__.strip())
        return 0
    try:
        from kame.qt_quit import quit_on_signals
        from kame.rqt.console_window import application
        from kame.rqt.logger_window import LoggerWindow
    except ImportError as exc:
        print(f"rqt_logger_level needs PySide6 (pip install 'kame[gui]'): {exc}", file=sys.stderr)
        return 1
    import os

    from kame.rqt.logger_source import LoggerLevels
    from kame.rqt.ros_node import master_uri

    app = application("rqt_logger_level")
    quit_on_signals(app)  # Ctrl-C closes the tool as its window does
    levels = LoggerLevels(master_uri(ros.special), f"/rqt_logger_level_{os.getpid()}")
    window = LoggerWindow(levels)
    try:
        window.show()
        window.refresh()
        return int(app.exec())
    finally:
        window.close_worker()
        levels.close()


if __name__ == "__main__":
    sys.exit(main())
