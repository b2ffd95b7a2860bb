"""rosout: the node that aggregates every node's log records (`rosout __name:=rosout __log:=FILE`).

What it does, as ros_comm's C++ rosout (1.15.15) does it (spec ros1-interop §8.2):
- subscribes to /rosout (rosgraph_msgs/Log) and republishes every message, byte for byte, on
  /rosout_agg (not latched, no queue limit);
- writes `rosout.log` next to its `__log` file (else in the log dir), opened fresh with
  `\\n\\n<stamp>  Node Startup`, one line per record:
  `<secs>.<nsecs:09> <LEVEL> <node> [<file>:<line>(<function>)] [topics: a, b] <msg>`,
  the `[topics: ...]` part left out while the parameter /rosout/omit_topics is true;
  rotated past 100 MB into rosout.log.1 ... .10 (the oldest dropped);
- writes no file when ROSOUT_DISABLE_FILE_LOGGING is set to anything but '', 0, false, off, no;
- offers /rosout/get_loggers and /rosout/set_logger_level (roscpp's logger services).

Built on kame.node rather than the rospy facade: a relay wants the raw frames (rospy would
copy each into an AnyMsg and serialize it back), and rosout, like roscpp's NoRosout, must not
publish its own records to /rosout. Frames are parsed once, straight from the wire bytes,
into the few fields the file line needs; the strings stay bytes and go to the file as they came.
A frame that does not parse as a Log is dropped, as roscpp drops what it cannot deserialize.
"""

from __future__ import annotations

import logging
import os
import struct
import sys
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, BinaryIO, NamedTuple

from kame import names
from kame.cli._node import ToolNode
from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.node.topics import Publication, serialize_payload

LOGGER = "kame.rosout"  # not __name__, which is __main__ under python -m
log = logging.getLogger(LOGGER)

MAX_FILE_SIZE = 100 * 1024 * 1024
MAX_BACKUPS = 10
OMIT_TOPICS_PARAM = "/rosout/omit_topics"
LOG_TYPE = "rosgraph_msgs/Log"

_LEVELS = {16: b"FATAL", 8: b"ERROR", 4: b"WARN", 1: b"DEBUG", 2: b"INFO"}
_U32 = struct.Struct("<I")
_HEAD = struct.Struct("<IIII")  # header.seq, header.stamp.secs, .nsecs, len(header.frame_id)
_TAIL = struct.Struct("<II")  # line, len(topics)
_LEVEL = struct.Struct("<b")


# ---------------------------------------------------------------------- pure: records and lines


class LogRecord(NamedTuple):
    """The fields of a rosgraph_msgs/Log that rosout.log shows; strings as the wire's bytes.

    A NamedTuple: a frozen dataclass costs a microsecond more per message to build."""

    secs: int
    nsecs: int
    level: int
    name: bytes
    msg: bytes
    file: bytes
    function: bytes
    line: int
    topics: tuple[bytes, ...]


class MalformedLog(ValueError):
    """The bytes are not a serialized rosgraph_msgs/Log (the sender's fault)."""


def parse_log(data: bytes | memoryview) -> LogRecord:
    """Read a serialized rosgraph_msgs/Log without building a message object."""
    buf = data if type(data) is bytes else bytes(data)  # one small copy; slicing bytes is the fast path
    size = len(buf)
    try:
        _seq, secs, nsecs, skip = _HEAD.unpack_from(buf, 0)
        pos = 16 + skip  # past frame_id
        (level,) = _LEVEL.unpack_from(buf, pos)
        pos += 1
        strings = []
        for _ in range(4):  # name, msg, file, function
            end = pos + 4 + _U32.unpack_from(buf, pos)[0]
            if end > size:
                raise MalformedLog("a string runs past the end of the message")
            strings.append(buf[pos + 4:end])
            pos = end
        line, count = _TAIL.unpack_from(buf, pos)
        pos += 8
        topics = []
        for _ in range(count):
            end = pos + 4 + _U32.unpack_from(buf, pos)[0]
            if end > size:
                raise MalformedLog("a topic name runs past the end of the message")
            topics.append(buf[pos + 4:end])
            pos = end
    except struct.error as exc:
        raise MalformedLog(f"truncated rosgraph_msgs/Log: {exc}") from exc
    name, msg, file, function = strings
    return LogRecord(secs, nsecs, level, name, msg, file, function, line, tuple(topics))


def format_stamp(secs: int, nsecs: int) -> str:
    """A ros::Time as roscpp streams it: seconds, a dot, nanoseconds padded to 9 digits."""
    return f"{secs}.{nsecs:09d}"


def format_line(record: LogRecord, omit_topics: bool = False) -> bytes:
    """One rosout.log line (with its newline), byte for byte as ROS's rosout writes it.

    A level that is none of the five constants is written as its raw byte, as roscpp streams an
    int8 (level 3 gives the byte 0x03).
    """
    level = _LEVELS.get(record.level)
    if level is None:
        level = bytes((record.level & 0xFF,))
    parts = [format_stamp(record.secs, record.nsecs).encode(), b" ", level, b" ", record.name, b" [",
             record.file, b":", str(record.line).encode(), b"(", record.function, b")] "]
    if not omit_topics:
        parts += [b"[topics: ", b", ".join(record.topics), b"] "]
    parts += [record.msg, b"\n"]
    return b"".join(parts)


def startup_line(now_ns: int) -> bytes:
    """What a fresh rosout.log starts with (two empty lines, then the start-up stamp)."""
    return f"\n\n{format_stamp(now_ns // 1_000_000_000, now_ns % 1_000_000_000)}  Node Startup\n".encode()


def file_logging_disabled(env: Mapping[str, str]) -> bool:
    value = env.get("ROSOUT_DISABLE_FILE_LOGGING", "")
    return value.lower() not in ("", "0", "false", "off", "no")


# ---------------------------------------------------------------------- the file


class RotatingLog:
    """rosout.log: truncated when opened; past `max_bytes` it becomes .1, .1 becomes .2, ...,
    keeping `backups` of them (the oldest removed), and a new empty file takes its place.

    The size counts what we wrote since the file was opened, checked after each line, as ROS does.
    """

    def __init__(self, path: Path, max_bytes: int = MAX_FILE_SIZE, backups: int = MAX_BACKUPS) -> None:
        self.path = path
        self.max_bytes = max_bytes
        self.backups = backups
        self.size = 0
        self._backup_index = 0
        self._file: BinaryIO | None = open(path, "wb")  # owned until close()

    def write(self, lines: Sequence[bytes]) -> None:
        """Append lines, rotating after any line that takes the file past its size limit."""
        pending: list[bytes] = []
        for line in lines:
            pending.append(line)
            self.size += len(line)
            if self.size > self.max_bytes:
                self._write(pending)
                pending = []
                self._rotate()
        if pending:
            self._write(pending)
        if self._file is not None:
            try:
                self._file.flush()
            except OSError as exc:
                print(f"Error flushing rosout log file '{self.path}': {exc.strerror}", file=sys.stderr, flush=True)

    def _write(self, lines: list[bytes]) -> None:
        if self._file is None:
            return
        try:
            self._file.write(b"".join(lines))
        except OSError as exc:
            print(f"Error writing to rosout log file '{self.path}': {exc.strerror}", file=sys.stderr, flush=True)

    def _rotate(self) -> None:
        print(f"rosout log file {self.path} reached max size, rotating log files", flush=True)
        self.close()
        if self.backups > 0:
            if self._backup_index == self.backups:
                Path(f"{self.path}.{self.backups}").unlink(missing_ok=True)
            for i in range(min(self.backups, self._backup_index + 1), 0, -1):
                source = self.path if i == 1 else Path(f"{self.path}.{i - 1}")
                try:
                    os.replace(source, f"{self.path}.{i}")
                except OSError as exc:
                    print(f"Error rotating rosout log file '{source}' to '{self.path}.{i}': {exc.strerror}",
                          file=sys.stderr, flush=True)
            self._backup_index = min(self._backup_index + 1, self.backups)
        try:
            self._file = open(self.path, "wb")
        except OSError as exc:
            print(f"Error opening rosout log file '{self.path}': {exc.strerror}", file=sys.stderr, flush=True)
        self.size = 0

    def close(self) -> None:
        if self._file is not None:
            try:
                self._file.close()
            except OSError:
                pass
            self._file = None


# ---------------------------------------------------------------------- the node


class Rosout:
    """The relay and the file, on a kame Node that this object sets up and the caller shuts down."""

    def __init__(self, node: Node, file: RotatingLog | None) -> None:
        from rosgraph_msgs.msg import Log

        self.node = node
        self.file = file
        self.dropped = 0
        self._subscribe_omit_topics()
        self.agg: Publication = node.advertise("/rosout_agg", LOG_TYPE, Log._md5sum, Log._full_text,
                                               latch=False, queue_size=0)
        print("re-publishing aggregated messages to /rosout_agg", flush=True)
        self._loggers = {"ros": "info", "ros.rosout": "info"}
        self._offer_logger_services()
        node.subscribe("/rosout", LOG_TYPE, Log._md5sum, Log._full_text, self.on_frames)
        print("subscribed to /rosout", flush=True)

    def _subscribe_omit_topics(self) -> None:
        try:
            self.node.cached_param(OMIT_TOPICS_PARAM)  # subscribed, and an update meanwhile kept
        except (OSError, MasterError) as exc:
            log.warning("cannot subscribe to %s: %s", OMIT_TOPICS_PARAM, exc)

    @property
    def omit_topics(self) -> bool:
        return self.node.param_cache.get(OMIT_TOPICS_PARAM) is True  # roscpp reads it as a bool only

    def on_frames(self, frames: list[memoryview], header: dict[str, str]) -> None:
        """Relay each message as it came and write its line (one subscription: never concurrent)."""
        lines = []
        omit = self.omit_topics
        for frame in frames:
            try:
                record = parse_log(frame)
            except MalformedLog as exc:
                self.dropped += 1
                log.error("dropping a message from %s on /rosout: %s", header.get("callerid", "?"), exc)
                continue
            # the subscription reuses its receive buffer after this call: borrowed
            self.agg.publish_payload(frame, borrowed=True)
            if self.file is not None:
                lines.append(format_line(record, omit))
        if lines and self.file is not None:
            self.file.write(lines)

    def _offer_logger_services(self) -> None:
        from roscpp.msg import Logger
        from roscpp.srv import GetLoggers, GetLoggersResponse, SetLoggerLevel, SetLoggerLevelRequest

        def get_loggers(request: bytes) -> tuple[bool, bytes | str]:
            loggers = [Logger(name=name, level=level) for name, level in sorted(self._loggers.items())]
            return True, serialize_payload(GetLoggersResponse(loggers=loggers))

        def set_logger_level(request: bytes) -> tuple[bool, bytes | str]:
            try:
                req: Any = SetLoggerLevelRequest().deserialize(request)
            except Exception as exc:
                return False, f"malformed request: {exc}"
            level = str(req.level).lower()
            if level not in _PY_LEVELS:
                return False, f"Invalid logger level [{req.level}]"
            self._loggers[str(req.logger)] = level
            if req.logger in _PY_LOGGERS:
                logging.getLogger(_PY_LOGGERS[req.logger]).setLevel(_PY_LEVELS[level])
            return True, b""

        name = self.node.name
        self.node.advertise_service(f"{name}/get_loggers", GetLoggers._type, GetLoggers._md5sum, get_loggers)
        self.node.advertise_service(f"{name}/set_logger_level", SetLoggerLevel._type, SetLoggerLevel._md5sum,
                                    set_logger_level)


_PY_LEVELS = {"debug": logging.DEBUG, "info": logging.INFO, "warn": logging.WARNING, "error": logging.ERROR,
              "fatal": logging.CRITICAL}
_PY_LOGGERS = {"ros": "kame", "ros.rosout": LOGGER}


def _log_dir(env: Mapping[str, str]) -> Path:
    """ROS_LOG_DIR, else ROS_HOME/log, else ~/.ros/log (spec §8.3); kame.cli.rosmaster has the same
    rule, but importing it (asyncio, the master) would add a third to rosout's start-up time."""
    if env.get("ROS_LOG_DIR"):
        return Path(env["ROS_LOG_DIR"])
    return (Path(env["ROS_HOME"]) if env.get("ROS_HOME") else Path.home() / ".ros") / "log"


def _open_file(log_arg: str | None, env: Mapping[str, str]) -> RotatingLog | None:
    if file_logging_disabled(env):
        return None
    directory = Path(log_arg).absolute().parent if log_arg else _log_dir(env)
    path = directory / "rosout.log"
    try:
        directory.mkdir(parents=True, exist_ok=True)
        file = RotatingLog(path)
    except OSError as exc:
        print(f"Error opening rosout log file '{path}': {exc.strerror}", file=sys.stderr, flush=True)
        return None
    print(f"logging to {path}", flush=True)
    file.write([startup_line(time.time_ns())])
    return file


def main(argv: Sequence[str] | None = None) -> int:
    ros = names.parse_args(sys.argv[1:] if argv is None else argv)
    special = ros.special
    tool = ToolNode(special, "rosout", ros.remappings)
    node, stop = tool.node, tool.stop
    file = None
    try:
        if not tool.wait_for_master():  # like roscpp, wait for the master to answer
            return 0
        file = _open_file(special.get("log"), os.environ)
        Rosout(node, file)
        stop.wait()
    finally:
        node.shutdown("rosout exiting")
        if file is not None:
            file.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
