"""tf_echo (tf's, `tf_echo source target [rate]`) and tf2_echo (tf2_tools' echo.py options):
print the pose of the target frame in the source frame at the latest time, `rate` times a
second, in the programs' own formats."""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence

from kame.cli._console import console
from kame.cli._node import ToolNode
from kame.cli._tf import listening_buffer, start_node, wall_seconds_text
from kame.tf import errors, rotation
from kame.tf.buffer_core import strip_slash

TF_ECHO_USAGE = """Usage: tf_echo source_frame target_frame [echo_rate]

This will echo the transform from the coordinate frame of the source_frame
to the coordinate frame of the target_frame. 
Note: This is the transform to get data from target_frame into the source_frame.
Default echo rate is 1 if echo_rate is not given.
"""  # noqa: W291 -- the program's own trailing space


def rpy(q: rotation.Quaternion) -> tuple[float, float, float]:
    """tf's Matrix3x3::getRPY (first solution)."""
    m = rotation.to_matrix(q)
    if abs(m[2][0]) >= 1:
        delta = math.atan2(m[2][1], m[2][2])
        return (delta, math.pi / 2 if m[2][0] < 0 else -math.pi / 2, 0.0)
    pitch = -math.asin(m[2][0])
    cos_pitch = math.cos(pitch)
    return (math.atan2(m[2][1] / cos_pitch, m[2][2] / cos_pitch), pitch,
            math.atan2(m[1][0] / cos_pitch, m[0][0] / cos_pitch))


def _triple(values: Sequence[float], precision: int) -> str:
    return ", ".join(f"{v:.{precision}f}" for v in values)


def main(argv: Sequence[str] | None = None) -> int:
    tool, args = start_node(sys.argv[1:] if argv is None else argv, "tf_echo")
    try:
        if len(args) not in (2, 3):
            print(TF_ECHO_USAGE, end="", flush=True)
            return 255
        if not tool.wait_for_master():
            return 0
        rate = _number(args[2]) if len(args) == 3 else _param(tool, "rate", 1.0)
        if rate <= 0.0:
            sys.stderr.write("Echo rate must be > 0.0\n")
            return 255
        precision = int(_param(tool, "precision", 3))
        if precision < 1:
            sys.stderr.write("Precision must be > 0\n")
            return 255
        buffer, _ = listening_buffer(tool)
        source, target = strip_slash(args[0]), strip_slash(args[1])
        buffer.can_transform(source, target, 0, 1.0)  # up to a second for the first data
        while not tool.stop.is_set():
            try:
                found = buffer.lookup_transform(source, target, 0)
                t, r = found.transform.translation, found.transform.rotation
                # tf keeps a rotation matrix; its quaternion comes back from that matrix
                q = rotation.from_matrix(rotation.to_matrix((r.x, r.y, r.z, r.w)))
                angles = rpy(q)
                stamp = found.header.stamp.to_nsec() / 1e9
                print(f"At time {stamp:.{precision}f}\n"
                      f"- Translation: [{_triple((t.x, t.y, t.z), precision)}]\n"
                      f"- Rotation: in Quaternion [{_triple(q, precision)}]\n"
                      f"            in RPY (radian) [{_triple(angles, precision)}]\n"
                      f"            in RPY (degree) [{_triple([a * 180.0 / math.pi for a in angles], precision)}]",
                      flush=True)
            except errors.TransformException as exc:
                print(f"Failure at {wall_seconds_text(tool.now_ns())}\nException thrown:{exc}\n"
                      f"The current list of frames is:\n{buffer.all_frames_as_string()}", flush=True)
            tool.stop.wait(1.0 / rate)
        return 0
    finally:
        tool.node.shutdown("tf_echo exiting")


def _number(text: str) -> float:
    """atof: what does not parse is 0."""
    try:
        return float(text)
    except ValueError:
        return 0.0


def _param(tool: ToolNode, name: str, default: float) -> float:
    """A private parameter (`_rate:=5`, or set in a launch file), else the default."""
    try:
        value = tool.node.master.call("getParam", tool.node.resolve("~" + name))
    except Exception:
        return default
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else default


def _positive(kind: type[float] | type[int]) -> argparse._ActionType:
    def check(text: str) -> float | int:
        value = kind(text)
        if value <= 0:
            raise argparse.ArgumentTypeError(f"{value} must be > {'0.0' if kind is float else '0'}")
        return value
    return check


def main_tf2(argv: Sequence[str] | None = None) -> int:
    """tf2_tools' echo.py."""
    tool, args = start_node(sys.argv[1:] if argv is None else argv, "echo", anonymous=False)
    parser = argparse.ArgumentParser(prog="echo.py")
    parser.add_argument("source_frame")
    parser.add_argument("target_frame")
    parser.add_argument("-r", "--rate", help="update rate, must be > 0.0", default=1.0, type=_positive(float))
    parser.add_argument("-c", "--cache_time", help="length of tf buffer cache in seconds", type=_positive(float))
    parser.add_argument("-o", "--offset", help="offset the lookup from current time, ignored if using -t", type=float)
    parser.add_argument("-t", "--time", help="fixed time to do the lookup", type=float)
    parser.add_argument("-l", "--limit", help="lookup fixed number of times", type=_positive(int))
    parser.add_argument("-p", "--precision", help="output precision", default=3, type=_positive(int))
    try:
        options = parser.parse_args(args)
        if not tool.wait_for_master():
            return 0
        buffer, _ = listening_buffer(tool)
        count = 0
        while not tool.stop.wait(1.0 / options.rate):
            count += 1
            if options.limit and count > options.limit:
                return 0
            now = tool.now_ns()
            if options.time:
                lookup = round(options.time * 1e9)
            elif options.offset:
                lookup = now + round(options.offset * 1e9)
            else:
                lookup = 0
            try:
                found = buffer.lookup_transform(options.source_frame, options.target_frame, lookup)
            except errors.LookupException as exc:
                console("ERROR", f"At time {lookup / 1e9}, (current time {now / 1e9}) {exc}")
                continue
            except errors.ExtrapolationException as exc:
                console("ERROR", f"(current time {now / 1e9}) {exc}")
                continue
            p = options.precision
            t, r = found.transform.translation, found.transform.rotation
            roll, pitch, yaw = _echo_euler((r.x, r.y, r.z, r.w))
            print(f"At time {found.header.stamp.to_nsec() / 1e9}, (current time {now / 1e9})\n"
                  f"- Translation: [{_triple((t.x, t.y, t.z), p)}]\n"
                  f"- Rotation: in Quaternion [{_triple((r.x, r.y, r.z, r.w), p)}]\n"
                  f"            in RPY (radian) [{_triple((roll, pitch, yaw), p)}]\n"
                  f"            in RPY (degree) [{_triple([math.degrees(a) for a in (roll, pitch, yaw)], p)}]",
                  flush=True)
        return 0
    except SystemExit as exc:  # argparse's usage errors
        return int(exc.code or 0)
    finally:
        tool.node.shutdown("echo exiting")


def _echo_euler(q: rotation.Quaternion) -> tuple[float, float, float]:
    """echo.py's own sxyz Euler angles (the tf.transformations arithmetic)."""
    from kame.tf.transformations import euler_from_quaternion

    return euler_from_quaternion(q)


if __name__ == "__main__":
    sys.exit(main())
