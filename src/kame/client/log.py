"""Logging of a program's node: the console lines ROS users know, a log file per node, /rosout.

Console: `[INFO] [1795311282.956206]: text` (ROSCONSOLE_FORMAT overrides the template),
DEBUG and INFO to stdout, WARN and above to stderr, coloured on a tty only; a port of a C++
program prints roscpp's lines instead (use_roscpp_console, kame.console). Every record
at or above the node's level is also published on /rosout (rosgraph_msgs/Log) straight to
the connected subscribers: no master round trip per call. The file gets Python logging's
lines in rospy's format under ROS_LOG_DIR (or ROS_HOME/log, or ~/.ros/log).
"""

from __future__ import annotations

import logging
import os
import sys
import threading
import time
from collections.abc import Callable
from typing import Any

from kame.client import core
from kame.console import RESET, coloured, roscpp_colour, roscpp_stamp

DEBUG, INFO, WARN, ERROR, FATAL = 1, 2, 4, 8, 16
LEVEL_NAMES = {DEBUG: "DEBUG", INFO: "INFO", WARN: "WARN", ERROR: "ERROR", FATAL: "FATAL"}
PY_LEVELS = {DEBUG: logging.DEBUG, INFO: logging.INFO, WARN: logging.WARNING, ERROR: logging.ERROR,
             FATAL: logging.CRITICAL}
_COLOURS = {DEBUG: "\033[32m", WARN: "\033[33m", ERROR: "\033[31m", FATAL: "\033[31m"}
DEFAULT_FORMAT = "[${severity}] [${time}]: ${message}"

_level = INFO
_rosout_publish: Callable[[int, str, str, str, int], None] | None = None
_file_logger = logging.getLogger("rosout")
_lock = threading.Lock()
_once: set[Any] = set()
_throttle_last: dict[Any, float] = {}
_identical_last: dict[Any, tuple[str, float]] = {}
_roscpp_console = False  # roscpp's look: `[ INFO] [1795311282.956206123]: text`


def set_level(level: int) -> None:
    global _level
    _level = level


def get_level() -> int:
    return _level


def set_rosout_publisher(publish: Callable[[int, str, str, str, int], None] | None) -> None:
    global _rosout_publish
    _rosout_publish = publish


def use_roscpp_console(on: bool = True) -> None:
    """Console lines as a roscpp node prints them (severity padded to 5, time in nanoseconds):
    for kame's ports of C++ programs (turtlesim), whose users know those lines."""
    global _roscpp_console
    _roscpp_console = on


def roscpp_console() -> bool:
    """Whether this program prints roscpp's console lines (use_roscpp_console)."""
    return _roscpp_console


def log_dir() -> str:
    if os.environ.get("ROS_LOG_DIR"):
        return os.environ["ROS_LOG_DIR"]
    home = os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    return os.path.join(home, "log")


def configure_file_logging(node_name: str, log_file: str | None) -> None:
    """rospy's per-node log file: `__log:=` when roslaunch gives one, else `<log dir>/<name>.log`."""
    path = log_file or os.path.join(log_dir(), node_name.lstrip("/").replace("/", "_") + ".log")
    try:
        os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
        handler = logging.FileHandler(path)
    except OSError:
        return
    handler.setFormatter(logging.Formatter("[%(name)s][%(levelname)s] %(asctime)s: %(message)s"))
    root = logging.getLogger()
    root.addHandler(handler)
    root.setLevel(logging.DEBUG if _level == DEBUG else logging.INFO)


def _time_text() -> str:
    from kame.client import clock

    wall = f"{time.time():.6f}"
    if clock.is_sim_time() and clock.is_rostime_initialized():
        return f"{wall}, {clock.get_time():.6f}"
    return wall


def _console(level: int, text: str, file: str, line: int, function: str) -> None:
    template = os.environ.get("ROSCONSOLE_FORMAT", DEFAULT_FORMAT)
    severity, stamp = LEVEL_NAMES[level], _time_text()
    if _roscpp_console:
        severity, stamp = f"{severity:>5}", roscpp_stamp(time.time_ns())
    fields = {
        "severity": severity, "time": stamp, "message": text, "node": core.get_caller_id(),
        "logger": "rosout", "file": file, "line": str(line), "function": function,
        "thread": threading.current_thread().name, "walltime": f"{time.time():.6f}",
    }
    out = template
    for key, value in fields.items():
        out = out.replace("${" + key + "}", value)
    stream = sys.stdout if level <= INFO else sys.stderr
    if _roscpp_console:  # rosconsole colours every line, to a terminal or not
        out = coloured(LEVEL_NAMES[level], out, roscpp_colour(os.environ)) + "\n"
    elif level in _COLOURS and stream.isatty():  # rospy only on a terminal, its reset after the newline
        out = _COLOURS[level] + out + "\n" + RESET
    else:
        out += "\n"
    try:
        stream.write(out)
        stream.flush()
    except (OSError, ValueError):
        pass


def _caller(depth: int) -> tuple[str, int, str, Any]:
    try:
        frame: Any = sys._getframe(depth)
    except ValueError:
        frame = None
    if frame is None:
        return "?", 0, "?", None
    code = frame.f_code
    function = code.co_name
    owner = frame.f_locals.get("self")
    if owner is not None:
        function = f"{type(owner).__name__}.{function}"
    return os.path.basename(code.co_filename), frame.f_lineno, function, (code.co_filename, frame.f_lineno)


def emit(level: int, msg: Any, args: tuple[Any, ...], depth: int = 3, caller: tuple[str, int, str, Any] | None = None,
         logger_name: str = "rosout") -> None:
    if level < _level:
        return
    text = str(msg) % args if args else str(msg)
    file, line, function, _ = caller or _caller(depth)
    _console(level, text, file, line, function)
    _file_logger.log(PY_LEVELS[level], text)
    to_rosout(level, text, file, function, line)


def to_rosout(level: int, text: str, file: str, function: str, line: int) -> None:
    """Publish a log line on /rosout only (not the console or log file); nothing before the
    node's /rosout publisher is up."""
    publish = _rosout_publish
    if publish is not None:
        try:
            publish(level, text, file, function, line)
        except Exception:  # logging must never fail the caller; /rosout may be shutting down
            pass


_FROM_PY = {logging.DEBUG: DEBUG, logging.INFO: INFO, logging.WARNING: WARN, logging.ERROR: ERROR,
            logging.CRITICAL: FATAL}


def level_of(levelno: int) -> int:
    """The ROS level of a Python logging level (ERROR for one between them)."""
    return _FROM_PY.get(levelno, ERROR)


class _RuntimeRecords(logging.Handler):
    """Warnings and errors of kame's runtime (a refused connection, a bad peer) reach the
    console and /rosout like rospy's own internal messages do."""

    def emit(self, record: logging.LogRecord) -> None:
        level = level_of(record.levelno)
        try:
            text = record.getMessage()
        except Exception:
            text = str(record.msg)
        emit(level, text, (), caller=(record.filename, record.lineno, record.funcName, None))


def route_runtime_logs() -> None:
    runtime = logging.getLogger("kame")
    if not any(isinstance(h, _RuntimeRecords) for h in runtime.handlers):
        runtime.addHandler(_RuntimeRecords(logging.WARNING))
        runtime.propagate = False  # the handler writes them to the node's log file already


def route_program_logs(name: str) -> None:
    """A program's own logger (`name`, under "kame") from INFO up to the console and /rosout, as
    its ROS original's ROS_INFO lines are (foxglove_bridge's clients coming and going)."""
    logger = logging.getLogger(name)
    if not any(isinstance(h, _RuntimeRecords) for h in logger.handlers):
        logger.setLevel(logging.INFO)
        logger.addHandler(_RuntimeRecords(logging.INFO))
        logger.propagate = False


def emit_once(level: int, msg: Any, args: tuple[Any, ...]) -> None:
    caller = _caller(3)
    with _lock:
        if caller[3] in _once:
            return
        _once.add(caller[3])
    emit(level, msg, args, caller=caller)


def emit_throttle(period: float, level: int, msg: Any, args: tuple[Any, ...]) -> None:
    caller = _caller(3)
    now = _now()
    with _lock:
        last = _throttle_last.get(caller[3])
        if last is not None and now - last < period:
            return
        _throttle_last[caller[3]] = now
    emit(level, msg, args, caller=caller)


def emit_throttle_identical(period: float, level: int, msg: Any, args: tuple[Any, ...]) -> None:
    caller = _caller(3)
    text = str(msg) % args if args else str(msg)
    now = _now()
    with _lock:
        last = _identical_last.get(caller[3])
        if last is not None and last[0] == text and now - last[1] < period:
            return
        _identical_last[caller[3]] = (text, now)
    emit(level, text, (), caller=caller)


def _now() -> float:
    from kame.client import clock

    if clock.is_rostime_initialized():
        return clock.get_time()
    return time.time()
