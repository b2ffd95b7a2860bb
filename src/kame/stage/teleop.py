"""turtlebot_teleop_key: drive a TurtleBot from this terminal, as turtlebot_teleop's script does.

Node `turtlebot_teleop` (keyboard_teleop.launch names it turtlebot_teleop_keyboard), publishing
geometry_msgs/Twist on `~cmd_vel` about ten times a second (every key, or every 0.1 s without
one). Keys u i o / j k l / m , . choose a direction, q/z w/x e/c scale the speeds by 10 %, space
or k stops at once, anything else (or five quiet ticks) stops smoothly; the speed ramps by
0.02 m/s and the turn by 0.1 rad/s per tick toward the target, from 0.2 m/s and 1 rad/s. Ctrl-C
quits with a stop command. The terminal is raw only while a key is awaited and is restored
however it ends; a stdin that is no terminal (a pipe) is read as it comes.
"""

from __future__ import annotations

import contextlib
import os
import select
import sys
import termios
import tty
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

from kame.stage import runtime

BANNER = """
Control Your Turtlebot!
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%
space key, k : force stop
anything else : stop smoothly

CTRL-C to quit
"""

MOVES = {"i": (1, 0), "o": (1, -1), "j": (0, 1), "l": (0, -1), "u": (1, 1), ",": (-1, 0), ".": (-1, 1),
         "m": (-1, -1)}
SCALES = {"q": (1.1, 1.1), "z": (0.9, 0.9), "w": (1.1, 1.0), "x": (0.9, 1.0), "e": (1.0, 1.1), "c": (1.0, 0.9)}
TICK = 0.1  # seconds without a key before the script publishes again
CTRL_C = "\x03"


def speeds_line(speed: float, turn: float) -> str:
    return f"currently:\tspeed {speed}\tturn {turn} "


@dataclass
class Teleop:
    """The script's state: what each key (or a quiet tick, key '') does to the command."""

    speed: float = 0.2
    turn: float = 1.0
    x: int = 0
    th: int = 0
    quiet: int = 0
    status: int = 0
    control_speed: float = 0.0
    control_turn: float = 0.0

    def press(self, key: str) -> list[str]:
        """Take one key ('' for none); returns the lines the script prints."""
        printed: list[str] = []
        if key in MOVES:
            self.x, self.th = MOVES[key]
            self.quiet = 0
        elif key in SCALES:
            self.speed *= SCALES[key][0]
            self.turn *= SCALES[key][1]
            self.quiet = 0
            printed.append(speeds_line(self.speed, self.turn))
            if self.status == 14:
                printed.append(BANNER)
            self.status = (self.status + 1) % 15
        elif key in (" ", "k"):
            self.x = self.th = 0
            self.control_speed = self.control_turn = 0.0
        else:
            self.quiet += 1
            if self.quiet > 4:
                self.x = self.th = 0
        target_speed, target_turn = self.speed * self.x, self.turn * self.th
        self.control_speed = _ramp(self.control_speed, target_speed, 0.02)
        self.control_turn = _ramp(self.control_turn, target_turn, 0.1)
        return printed


def _ramp(current: float, target: float, most: float) -> float:
    if target > current:
        return min(target, current + most)
    if target < current:
        return max(target, current - most)
    return target


@contextlib.contextmanager
def _raw(fd: int) -> Iterator[None]:
    """Raw mode for one key (Ctrl-C arrives as a byte), restored after it as the script does."""
    try:
        saved = termios.tcgetattr(fd)
    except termios.error:
        yield  # not a terminal
        return
    tty.setraw(fd)
    try:
        yield
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)


def read_key(fd: int, timeout: float) -> str | None:
    """One key within `timeout` ('' when none came), or None at the end of input."""
    with _raw(fd):
        ready, _, _ = select.select([fd], [], [], timeout)
        if not ready:
            return ""
        data = os.read(fd, 1)
    return data.decode("latin-1") if data else None


def main(argv: Sequence[str] | None = None) -> int:
    from geometry_msgs.msg import Twist

    runtime.init("turtlebot_teleop", list(sys.argv if argv is None else argv))
    publisher = runtime.Publisher("~cmd_vel", Twist, queue_size=5)
    state = Teleop()
    print(BANNER)
    print(speeds_line(state.speed, state.turn), flush=True)
    fd = sys.stdin.fileno()
    try:
        while not runtime.is_shutdown():
            key = read_key(fd, TICK)
            if key is None or key == CTRL_C:
                break
            for line in state.press(key):
                print(line, flush=True)
            twist = Twist()
            twist.linear.x = state.control_speed
            twist.angular.z = state.control_turn
            publisher.publish(twist)
    except (KeyboardInterrupt, OSError):
        pass
    finally:
        publisher.publish(Twist())
        runtime.signal_shutdown("teleop quit")
    return 0


if __name__ == "__main__":
    sys.exit(main())
