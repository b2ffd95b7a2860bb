"""The rosout node's pure parts: reading Log messages off the wire, its rosout.log lines, rotation.

The expected lines were written by ROS's own rosout (Debian's /usr/lib/rosout/rosout 1.15.15)
for the same messages published with `rostopic pub`.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from kame.cli.rosout import (
    LogRecord,
    MalformedLog,
    RotatingLog,
    file_logging_disabled,
    format_line,
    format_stamp,
    parse_log,
    startup_line,
)
from kame.node.topics import serialize_payload
from rosgraph_msgs.msg import Log


def wire(**fields: object) -> bytes:
    msg = Log(**{k: v for k, v in fields.items() if k not in ("secs", "nsecs")})
    msg.header.stamp.secs = fields.get("secs", 12)
    msg.header.stamp.nsecs = fields.get("nsecs", 5)
    msg.header.seq = 7
    msg.header.frame_id = "frame"
    return serialize_payload(msg)


def line_of(omit_topics: bool = False, **fields: object) -> bytes:
    return format_line(parse_log(memoryview(wire(**fields))), omit_topics)


def test_parse_reads_every_field_from_the_wire() -> None:
    data = wire(level=4, name="/x", msg="héllo", file="f.py", function="fn", line=7, topics=["/a", "/b"],
                secs=1795316971, nsecs=34126353)
    assert parse_log(data) == LogRecord(1795316971, 34126353, 4, b"/x", "héllo".encode(), b"f.py", b"fn", 7,
                                        (b"/a", b"/b"))


@pytest.mark.parametrize(("fields", "omit", "expected"), [
    ({"level": 4, "topics": ["/a", "/b"], "msg": "hello world"}, False,
     b"12.000000005 WARN /x [f.py:7(fn)] [topics: /a, /b] hello world\n"),
    ({"level": 3, "topics": [], "msg": "lvl3"}, False, b"12.000000005 \x03 /x [f.py:7(fn)] [topics: ] lvl3\n"),
    ({"level": 2, "topics": ["/a"], "msg": "omitted"}, True, b"12.000000005 INFO /x [f.py:7(fn)] omitted\n"),
])
def test_lines_as_ros_rosout_writes_them(fields: dict[str, object], omit: bool, expected: bytes) -> None:
    assert line_of(omit, name="/x", file="f.py", function="fn", line=7, **fields) == expected


@pytest.mark.parametrize(("level", "text"), [(1, b"DEBUG"), (2, b"INFO"), (4, b"WARN"), (8, b"ERROR"),
                                             (16, b"FATAL"), (-1, b"\xff")])
def test_level_names(level: int, text: bytes) -> None:
    assert line_of(level=level).split(b" ")[1] == text


def test_strings_keep_their_bytes_and_the_stamp_its_nine_digits() -> None:
    line = line_of(level=8, name="/ns/n", msg="multi\nline ünï", file="/src/a.cpp", function="A::b", line=4294967295,
                   secs=0, nsecs=999999999)
    assert line == "0.999999999 ERROR /ns/n [/src/a.cpp:4294967295(A::b)] [topics: ] multi\nline ünï\n".encode()
    assert format_stamp(5, 1) == "5.000000001"
    assert format_stamp(5, 1_500_000_000) == "5.1500000000"  # not normalised, as roscpp streams it


def test_startup_line() -> None:
    assert startup_line(1795316971_034126353) == b"\n\n1795316971.034126353  Node Startup\n"


@pytest.mark.parametrize("cut", [0, 3, 12, 17, 20, 40, -5, -1])
def test_truncated_messages_are_refused(cut: int) -> None:
    data = wire(level=2, name="/x", msg="hello", topics=["/a"])
    with pytest.raises(MalformedLog):
        parse_log(data[:cut])


def test_a_string_longer_than_the_message_is_refused() -> None:
    data = bytearray(wire(level=2, name="/x"))
    data[22:26] = (1 << 30).to_bytes(4, "little")  # the length of `name`
    with pytest.raises(MalformedLog):
        parse_log(bytes(data))


@pytest.mark.parametrize(("value", "disabled"), [
    (None, False), ("", False), ("0", False), ("false", False), ("FALSE", False), ("Off", False), ("no", False),
    ("1", True), ("true", True), ("yes", True), ("anything", True),
])
def test_rosout_disable_file_logging(value: str | None, disabled: bool) -> None:
    env = {} if value is None else {"ROSOUT_DISABLE_FILE_LOGGING": value}
    assert file_logging_disabled(env) is disabled


def test_the_file_is_truncated_when_opened(tmp_path: Path) -> None:
    path = tmp_path / "rosout.log"
    path.write_bytes(b"old contents\n")
    log = RotatingLog(path)
    log.write([b"new\n"])
    assert path.read_bytes() == b"new\n"
    log.close()


def test_rotation_shifts_the_backups_and_drops_the_oldest(tmp_path: Path) -> None:
    path = tmp_path / "rosout.log"
    log = RotatingLog(path, max_bytes=10, backups=3)
    # each 6-byte line; the file rotates after the line that takes it past 10 bytes
    log.write([f"line{i}\n".encode() for i in range(4)])  # 0,1 -> .1 ; 2,3 -> .1 (0,1 -> .2)
    assert path.read_bytes() == b""
    assert Path(f"{path}.1").read_bytes() == b"line2\nline3\n"
    assert Path(f"{path}.2").read_bytes() == b"line0\nline1\n"
    for i in range(4, 10):
        log.write([f"line{i}\n".encode()])
    log.close()
    assert path.read_bytes() == b""
    assert Path(f"{path}.1").read_bytes() == b"line8\nline9\n"
    assert Path(f"{path}.2").read_bytes() == b"line6\nline7\n"
    assert Path(f"{path}.3").read_bytes() == b"line4\nline5\n"
    assert not Path(f"{path}.4").exists()  # line0..3 fell off the end
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rosout.log", "rosout.log.1", "rosout.log.2",
                                                          "rosout.log.3"]


def test_without_backups_the_file_starts_over(tmp_path: Path) -> None:
    path = tmp_path / "rosout.log"
    log = RotatingLog(path, max_bytes=10, backups=0)
    log.write([b"aaaaaa\n", b"bbbbbb\n", b"cc\n"])
    log.close()
    assert path.read_bytes() == b"cc\n"
    assert list(tmp_path.iterdir()) == [path]


def test_default_limits_are_ros_ones(tmp_path: Path) -> None:
    log = RotatingLog(tmp_path / "rosout.log")
    assert (log.max_bytes, log.backups) == (100 * 1024 * 1024, 10)
    log.close()
