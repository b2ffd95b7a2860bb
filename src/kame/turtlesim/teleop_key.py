"""turtle_teleop_key: drive turtle1 with the arrow keys of this terminal.

As turtlesim's teleop_turtle_key: node `teleop_turtle`, publishes geometry_msgs/Twist on the
relative `turtle1/cmd_vel` (queue 1), one message per key press: Up/Down linear.x = +/-
scale_linear, Left/Right angular.z = +/- scale_angular (params looked up in the node's
namespace, default 2.0). Arrow keys arrive as ESC [ A..D and only the last byte counts, so
A/B/C/D also drive. `q` or Ctrl-C quits. The terminal (a local one, ssh's or tmux's pty) is
put in non-canonical no-echo mode while it runs and restored however it ends; a stdin that is
no terminal (a pipe) is read as it comes.
"""

from __future__ import annotations

import contextlib
import os
import select
import sys
import termios
from collections.abc import Iterator, Sequence
from typing import Any

from geometry_msgs.msg import Twist
from kame.client import core, log, process, topics

KEYCODE_UP, KEYCODE_DOWN, KEYCODE_RIGHT, KEYCODE_LEFT, KEYCODE_Q = 0x41, 0x42, 0x43, 0x44, 0x71
BANNER = """Reading from keyboard
---------------------------
Use arrow keys to move the turtle. 'q' to quit."""


@contextlib.contextmanager
def raw_terminal(fd: int) -> Iterator[None]:
    """No line buffering, no echo (signals stay on, so Ctrl-C still interrupts); restored on exit."""
    try:
        saved = termios.tcgetattr(fd)
    except termios.error:
        yield  # not a terminal
        return
    raw = termios.tcgetattr(fd)
    raw[3] &= ~(termios.ICANON | termios.ECHO)
    raw[6][termios.VMIN] = 1
    raw[6][termios.VTIME] = 0
    termios.tcsetattr(fd, termios.TCSANOW, raw)
    try:
        yield
    finally:
        termios.tcsetattr(fd, termios.TCSANOW, saved)


def twist_for(key: int, scale_linear: float, scale_angular: float) -> Twist | None:
    """The message one key byte sends, or None for a byte that does nothing."""
    linear = {KEYCODE_UP: 1.0, KEYCODE_DOWN: -1.0}.get(key, 0.0)
    angular = {KEYCODE_LEFT: 1.0, KEYCODE_RIGHT: -1.0}.get(key, 0.0)
    if not (linear or angular):
        return None
    twist = Twist()
    twist.linear.x = scale_linear * linear
    twist.angular.z = scale_angular * angular
    return twist


def _param(name: str, default: float) -> float:
    value: Any = process.get_param(name, default)
    try:
        return float(value)
    except (TypeError, ValueError):
        return default


def main(argv: Sequence[str] | None = None) -> int:
    log.use_roscpp_console()  # a C++ program in ROS
    process.init_node("teleop_turtle", argv=list(sys.argv if argv is None else argv))
    scale_angular = _param("scale_angular", 2.0)
    scale_linear = _param("scale_linear", 2.0)
    publisher = topics.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
    print(BANNER, flush=True)
    fd = sys.stdin.fileno()
    try:
        with raw_terminal(fd):
            while not core.is_shutdown():
                ready, _, _ = select.select([fd], [], [], 0.1)
                if not ready:
                    continue
                data = os.read(fd, 64)
                if not data:
                    break  # end of input
                for key in data:
                    if key == KEYCODE_Q:
                        return 0
                    twist = twist_for(key, scale_linear, scale_angular)
                    if twist is not None:
                        publisher.publish(twist)
    except (KeyboardInterrupt, OSError):
        pass
    finally:
        core.signal_shutdown("teleop quit")
    return 0


if __name__ == "__main__":
    sys.exit(main())
