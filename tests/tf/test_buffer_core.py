"""kame's tf2 buffer core against tf2's real one (Debian's tf2_py under /usr/bin/python3): the
same script of transforms and lookups must give the same transforms, the same exception
classes and the same messages, and the same warnings for refused data."""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path
from typing import Any

import pytest

from kame.tf import errors
from kame.tf.buffer_core import BufferCore, Transform

from ..support import SYSTEM_PYTHON

PEER = Path(__file__).with_name("debian_buffer_core.py")
S = 10**9
YAW90 = [0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)]
IDENTITY = [0.0, 0.0, 0.0, 1.0]


def have_tf2_py() -> bool:
    return subprocess.run([SYSTEM_PYTHON, "-c", "import tf2_py, rospy"], capture_output=True).returncode == 0


def yaw(angle: float) -> list[float]:
    return [0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2)]


SCRIPT: list[list[Any]] = [
    ["set", "world", "base", 1 * S, [1.0, 0.0, 0.0], yaw(0.0), "/mover", False],
    ["set", "world", "base", 2 * S, [2.0, 0.0, 0.0], yaw(1.0), "/mover", False],
    ["set", "world", "base", 3 * S, [3.0, 1.0, 0.0], yaw(2.0), "/mover", False],
    ["set", "base", "laser", 5 * S, [0.1, 0.0, 0.2], YAW90, "/static", True],
    ["set", "/world", "/other", 1 * S, [0.0, 5.0, 0.0], yaw(-1.0), "/o", False],
    ["set", "world", "other", 2500 * 10**6, [0.0, 6.0, 1.0], yaw(-0.5), "/o", False],
    ["set", "a", "b", 1 * S, [1.0, 2.0, 3.0], IDENTITY, "/island", False],
    ["lookup", "world", "laser", 0],
    ["lookup", "laser", "world", 0],
    ["lookup", "world", "laser", 1500 * 10**6],
    ["lookup", "world", "laser", 2 * S],
    ["lookup", "other", "laser", 0],
    ["lookup", "laser", "other", 2 * S],
    ["lookup", "laser", "laser", 0],
    ["lookup", "base", "laser", 7 * S],
    ["lookup", "world", "laser", 5 * S],
    ["lookup", "world", "laser", 500 * 10**6],
    ["lookup", "other", "base", 2800 * 10**6],
    ["lookup", "world", "b", 0],
    ["lookup", "world", "nowhere", 0],
    ["lookup", "", "base", 0],
    ["lookup", "/world", "base", 0],
    ["lookup", "b", "a", 0],
    ["lookup", "b", "a", 2 * S],
    ["lookup_full", "laser", 2 * S, "other", 1 * S, "world"],
    ["lookup_full", "laser", 2 * S, "b", 1 * S, "world"],
    ["lookup_full", "laser", 2 * S, "other", 1 * S, "nowhere"],
    ["lookup_full", "laser", 9 * S, "other", 1 * S, "world"],
    ["lookup", "other", "other", 0],
    ["lookup", "world", "world", 0],
    ["common", "laser", "laser"],
    ["can", "world", "laser", 0],
    ["can", "world", "laser", 9 * S],
    ["can", "world", "b", 0],
    ["can", "nowhere", "laser", 0],
    ["can", "nowhere", "gone", 0],
    ["can", "", "laser", 0],
    ["common", "laser", "other"],
    ["common", "world", "laser"],
    ["common", "laser", "base"],
    ["common", "base", "b"],
    ["string"],
    ["yaml"],
    ["dot"],
    ["dot", 12.5],
    ["set", "world", "base", 3 * S, [9.0, 9.0, 9.0], IDENTITY, "/again", False],
    ["set", "world", "base", 15 * S, [5.0, 0.0, 0.0], IDENTITY, "/mover", False],
    ["set", "world", "base", 4 * S, [9.0, 9.0, 9.0], IDENTITY, "/late", False],
    ["lookup", "world", "base", 4 * S],
    ["set", "world", "base", 4 * S, [math.nan, 0.0, 0.0], IDENTITY, "/nan", False],
    ["set", "world", "base", 4 * S, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], "/zero", False],
    ["set", "world", "world", 4 * S, [0.0, 0.0, 0.0], IDENTITY, "/self", False],
    ["set", "world", "", 4 * S, [0.0, 0.0, 0.0], IDENTITY, "/nochild", False],
    ["set", "", "base", 4 * S, [0.0, 0.0, 0.0], IDENTITY, "/noparent", False],
    ["lookup", "world", "base", 0],
    ["clear"],
    ["lookup", "base", "laser", 0],
    ["lookup", "world", "laser", 0],
    ["can", "world", "base", 0],
    ["set", "b", "a", 1 * S, [0.0, 0.0, 0.0], IDENTITY, "/loop", False],
    ["set", "a", "c", 1 * S, [0.0, 0.0, 0.0], IDENTITY, "/loop", False],
    ["lookup", "world", "c", 1 * S],
    ["string"],
    ["dot", 3.0],
]


def replay(core: BufferCore, script: list[list[Any]]) -> tuple[list[list[Any]], list[str]]:
    results: list[list[Any]] = []
    warnings: list[str] = []
    for op, *args in script:
        try:
            value: Any = None
            if op == "set":
                parent, child, ns, translation, rotation, authority, static = args
                warning = core.set_transform(Transform(parent, child, ns, translation, rotation), authority, static)
                if warning:
                    warnings.append(warning)
            elif op == "lookup":
                value = plain(core.lookup_transform(*args))
            elif op == "lookup_full":
                value = plain(core.lookup_transform_full(*args))
            elif op == "can":
                value = list(core.can_transform(*args))
            elif op == "common":
                value = core.latest_common_time(*args)
            elif op == "string":
                value = core.all_frames_as_string()
            elif op == "yaml":
                value = core.all_frames_as_yaml()
            elif op == "dot":
                value = core.all_frames_as_dot(*args)
            elif op == "clear":
                core.clear()
            results.append(["ok", value])
        except errors.TransformException as exc:
            results.append([type(exc).__name__, str(exc)])
    return results, warnings


def plain(t: Transform) -> list[Any]:
    return [t.parent, t.child, t.stamp, list(t.translation), list(t.rotation)]


def same(ours: Any, theirs: Any) -> bool:
    if isinstance(theirs, list):
        return isinstance(ours, list) and len(ours) == len(theirs) and all(
            same(a, b) for a, b in zip(ours, theirs, strict=True))
    if isinstance(theirs, float):
        return math.isclose(ours, theirs, rel_tol=1e-12, abs_tol=1e-12)
    return bool(ours == theirs)


@pytest.mark.skipif(not have_tf2_py(), reason="Debian's tf2_py is not installed")
def test_same_results_and_messages_as_tf2() -> None:
    done = subprocess.run([SYSTEM_PYTHON, str(PEER)], input=json.dumps({"cache_time": 10, "ops": SCRIPT}),
                          capture_output=True, text=True, check=True, timeout=60)
    theirs = json.loads(done.stdout)
    ours, warnings = replay(BufferCore(), SCRIPT)
    for step, a, b in zip(SCRIPT, ours, theirs, strict=True):
        assert same(a, b), f"{step}:\n kame: {a}\n tf2:  {b}"
    assert len(warnings) == 7
    # tf2 refuses a non-unit quaternion; kame normalizes it (with a warning): see the test below
    for warning in warnings:
        assert warning in done.stderr, f"{warning!r} not in tf2's output:\n{done.stderr}"


def test_a_non_unit_quaternion_is_normalized_with_a_warning_and_nan_is_refused() -> None:
    warnings: list[str] = []
    core = BufferCore(warn=warnings.append)
    assert core.set_transform(Transform("map", "robot", S, (1.0, 0.0, 0.0), (0.0, 0.0, 0.0, 2.0)), "/long") is None
    assert core.lookup_transform("map", "robot", 0).rotation == (0.0, 0.0, 0.0, 1.0)
    assert core.set_transform(Transform("map", "robot", 2 * S, (1.0, 0.0, 0.0), (0.0, 0.0, 3.0, 4.0)), "/long") is None
    assert core.lookup_transform("map", "robot", 0).rotation == pytest.approx((0.0, 0.0, 0.6, 0.8))
    assert warnings == [
        'TF_DENORMALIZED_QUATERNION: Normalizing the quaternion (0.000000 0.000000 0.000000 2.000000) of length '
        '2.000000 in the transform for child_frame_id "robot" from authority "/long"',
        'TF_DENORMALIZED_QUATERNION: Normalizing the quaternion (0.000000 0.000000 3.000000 4.000000) of length '
        '5.000000 in the transform for child_frame_id "robot" from authority "/long"']
    refused = core.set_transform(Transform("map", "robot", 3 * S, (1.0, 0.0, 0.0), (0.0, math.nan, 0.0, 1.0)), "/nan")
    assert refused == ('TF_NAN_INPUT: Ignoring transform for child_frame_id "robot" from authority "/nan" because '
                       "of a nan value in the transform (1.000000 0.000000 0.000000) (0.000000 nan 0.000000 1.000000)")
    infinite = core.set_transform(Transform("map", "robot", 3 * S, (0.0, 0.0, 0.0), (math.inf, 0.0, 0.0, 1.0)), "/i")
    assert infinite is not None and "because of an invalid quaternion" in infinite
    assert core.lookup_transform("map", "robot", 0).stamp == 2 * S


def test_interpolation_is_lerp_and_slerp() -> None:
    core = BufferCore()
    core.set_transform(Transform("map", "robot", 10 * S, (0.0, 0.0, 0.0), tuple(yaw(0.0))), "/a")
    core.set_transform(Transform("map", "robot", 12 * S, (2.0, 4.0, 0.0), tuple(yaw(1.0))), "/a")
    half = core.lookup_transform("map", "robot", 11 * S)
    assert half.translation == pytest.approx((1.0, 2.0, 0.0))
    assert half.rotation == pytest.approx(tuple(yaw(0.5)))
    assert half.stamp == 11 * S


def test_the_cache_keeps_ten_seconds_and_static_data_forever() -> None:
    core = BufferCore()
    core.set_transform(Transform("odom", "base", 0, (0.0, 0.0, 0.0), tuple(IDENTITY)), "/s", is_static=True)
    for second in range(1, 31):
        assert core.set_transform(Transform("map", "odom", second * S, (float(second), 0.0, 0.0),
                                            tuple(IDENTITY)), "/a") is None
    with pytest.raises(errors.ExtrapolationException, match="into the past"):
        core.lookup_transform("map", "base", 19 * S)
    assert core.lookup_transform("map", "base", 20 * S).translation == (20.0, 0.0, 0.0)
    assert core.lookup_transform("map", "base", 0).stamp == 30 * S
    core.clear()
    assert core.lookup_transform("odom", "base", 0).translation == (0.0, 0.0, 0.0)
    assert core.can_transform("map", "base", 0)[0] is False


def test_a_long_chain_composes_in_order() -> None:
    core = BufferCore()
    parent = "root"
    for index in range(50):
        child = f"link{index}"
        core.set_transform(Transform(parent, child, S, (1.0, 0.0, 0.0), tuple(yaw(math.pi / 25))), "/chain")
        parent = child
    # fifty unit steps turning 2*pi in all: the walk closes into a regular polygon
    tip = core.lookup_transform("root", "link49", 0)
    assert tip.translation == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    assert core.chain("root", "link3") == ["link3", "link2", "link1", "link0", "root"]
