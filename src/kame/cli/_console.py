"""The ros* tools that stand for C++ programs (rosbag, the tf tools, robot_state_publisher, ...)
print their messages as roscpp's console does (kame.console): INFO on stdout, the others on
stderr, each line flushed."""

from __future__ import annotations

import os
import sys
import time

from kame.console import roscpp_colour, roscpp_line


def console(level: str, text: str) -> None:
    """One roscpp console line at `level` (DEBUG, INFO, WARN, ERROR or FATAL), stamped now."""
    stream = sys.stdout if level in ("DEBUG", "INFO") else sys.stderr
    stream.write(roscpp_line(level, text, time.time_ns(), roscpp_colour(os.environ)) + "\n")
    stream.flush()
