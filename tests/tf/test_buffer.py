"""kame.tf_ros.Buffer: waits that wake when the transform arrives, timeouts, tf2's warnings
(the repeated-stamp one rate-limited), a clock jumping back, bad input never raising out of
the listener path."""

from __future__ import annotations

import math
import threading
import time

import pytest

from geometry_msgs.msg import TransformStamped
from kame.rostime import Duration, Time
from kame.tf import errors
from kame.tf_ros.buffer import Buffer


def transform(parent: str, child: str, secs: float, x: float = 0.0,
              q: tuple[float, ...] = (0, 0, 0, 1)) -> TransformStamped:
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = parent, child
    t.header.stamp = Time.from_sec(secs)
    t.transform.translation.x = x
    t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = q
    return t


def test_a_waiting_lookup_wakes_when_the_transform_arrives() -> None:
    buffer = Buffer()
    got: list[float] = []
    waiting = threading.Event()

    def look() -> None:
        waiting.set()
        got.append(buffer.lookup_transform("map", "robot", Time(), Duration(30)).transform.translation.x)

    thread = threading.Thread(target=look)
    thread.start()
    waiting.wait()
    buffer.set_transform(transform("map", "robot", 1.0, x=3.0), "/test")
    thread.join(30)
    assert got == [3.0]


def test_a_wait_ends_at_its_timeout_with_the_reason() -> None:
    buffer = Buffer()
    buffer.set_transform(transform("map", "robot", 1.0), "/test")
    ok, why = buffer.can_transform("map", "robot", Time(5), Duration(0.05), return_debug_tuple=True)
    assert not ok and why.startswith("Lookup would require extrapolation at time 5.000000000")
    with pytest.raises(errors.TimeoutException, match="ghost does not exist"):
        buffer.wait_for_transform("map", "ghost", Time(), 0.05)
    with pytest.raises(errors.LookupException):
        buffer.lookup_transform("map", "ghost", Time(), Duration(0.05))


def test_bad_transforms_are_refused_with_tf2s_errors() -> None:
    warnings: list[str] = []
    errors_seen: list[str] = []
    buffer = Buffer(warn=warnings.append, error=errors_seen.append)
    buffer.receive([transform("map", "a", 1.0, x=math.nan), transform("map", "b", 1.0, q=(0, 0, 0, 3)),
                    transform("map", "map", 1.0), transform("", "c", 1.0), transform("/map", "/d", 1.0)], "/bad",
                   is_static=False)
    assert [e.split(":")[0] for e in errors_seen] == ["TF_NAN_INPUT", "TF_SELF_TRANSFORM", "TF_NO_FRAME_ID"]
    assert [w.split(":")[0] for w in warnings] == ["TF_DENORMALIZED_QUATERNION"]  # normalized and kept
    assert buffer.frames() == ["b", "map", "d"]  # a leading slash is stripped on the way in
    assert buffer.lookup_transform("map", "b", Time()).transform.rotation.w == 1.0
    with pytest.raises(errors.InvalidArgumentException, match="cannot start with a '/'"):
        buffer.lookup_transform("/map", "d", Time())


def test_each_kind_of_bad_data_is_reported_once_per_interval() -> None:
    warnings: list[str] = []
    errors_seen: list[str] = []
    buffer = Buffer(warn=warnings.append, error=errors_seen.append)
    for index in range(50):
        buffer.set_transform(transform("map", "robot", 1.0), "/again")
        buffer.set_transform(transform("map", "arm", 1.0 + index, q=(0, 0, 0, 2)), "/long")
        buffer.set_transform(transform("map", "leg", 1.0 + index, x=math.nan), "/nan")
    assert warnings == [
        'TF_DENORMALIZED_QUATERNION: Normalizing the quaternion (0.000000 0.000000 0.000000 2.000000) of length '
        '2.000000 in the transform for child_frame_id "arm" from authority "/long"',
        "TF_REPEATED_DATA ignoring data with redundant timestamp for frame robot at time 1.000000 according to "
        "authority /again"]  # the first repeat comes with the second round
    assert len(errors_seen) == 1
    assert errors_seen[0].startswith('TF_NAN_INPUT: Ignoring transform for child_frame_id "leg"')
    assert buffer.lookup_transform("map", "arm", Time()).header.stamp == Time(50)  # all fifty kept, normalized


def test_a_clock_that_jumps_back_clears_all_but_static_data() -> None:
    warnings: list[str] = []
    buffer = Buffer(warn=warnings.append)
    now = time.time_ns()
    buffer.receive([transform("map", "odom", 100.0)], "/s", is_static=True, now=now)
    buffer.receive([transform("odom", "robot", 100.0)], "/d", is_static=False, now=now)
    buffer.receive([transform("odom", "robot", 1.0)], "/d", is_static=False, now=now - 50 * 10**9)
    assert warnings == ["Detected jump back in time of 50s. Clearing TF buffer."]
    assert buffer.lookup_transform("map", "robot", Time()).header.stamp == Time(1)



def test_messages_of_two_threads_are_never_taken_for_the_clock_going_back() -> None:
    """/tf and /tf_static arrive on threads of their own. One thread reads the clock, the other
    reads a later time and hands its message over first: handed over with the earlier time,
    the first message would look like a jump back and clear the buffer."""
    warnings: list[str] = []
    buffer = Buffer(warn=warnings.append)
    now = time.time_ns()
    first_has_read, second_done = threading.Event(), threading.Event()

    def first_clock() -> int:
        first_has_read.set()
        second_done.wait(0.5)  # held by the buffer's input order, the second cannot overtake
        return now

    def second() -> None:
        first_has_read.wait(5)
        buffer.receive_at([transform("map", "odom", 100.0)], "/s", True, lambda: now + 1000)
        second_done.set()

    overtaking = threading.Thread(target=second)
    overtaking.start()
    buffer.receive_at([transform("odom", "robot", 100.0)], "/d", False, first_clock)
    overtaking.join(5)
    assert warnings == []
    assert buffer.lookup_transform("map", "robot", Time()).header.stamp == Time(100)

def test_tf2_ros_buffer_core_is_tf2_pys() -> None:
    import rospy
    import tf2_ros

    core = tf2_ros.BufferCore(rospy.Duration(10))
    core.set_transform(transform("map", "robot", 1.0, x=2.0), "/core")
    assert core.lookup_transform_core("map", "robot", rospy.Time(0)).transform.translation.x == 2.0
    assert core.can_transform_core("map", "robot", rospy.Time(5)) == (
        False, "Lookup would require extrapolation at time 5.000000000, but only time 1.000000000 is in the buffer, "
        "when looking up transform from frame [robot] to frame [map]")
