"""Feeds rostopic.ROSTopicHz, ROSTopicBandwidth and ROSTopicDelay scripted arrival times and
prints what they report. Run by kame's interpreter and by Debian's /usr/bin/python3 (its real rostopic)."""

from __future__ import annotations

import io
import json
import sys
from contextlib import redirect_stdout
from typing import Any

import rostopic


class Clock:
    """Stands in for the time module rostopic reads wall time from."""

    def __init__(self) -> None:
        self.now = 0.0

    def time(self) -> float:
        return self.now


class Raw:
    def __init__(self, size: int) -> None:
        self._buff = b"x" * size


def run(request: dict[str, Any]) -> list[Any]:
    clock = Clock()
    rostopic.time = clock  # type: ignore[attr-defined]
    answers: list[Any] = []
    for case in request["hz"]:
        hz = rostopic.ROSTopicHz(case["window"], use_wtime=True)
        out = io.StringIO()
        reports = []
        with redirect_stdout(out):
            for step, (topic, at) in enumerate(case["arrivals"]):
                clock.now = at
                hz.callback_hz(None, topic)
                if step % 7 == 6:
                    reports.append([repr(hz.get_hz(t)) for t in case["topics"]])
                    if len(case["topics"]) == 1:  # upstream's table repeats a window (kame's does not)
                        hz.print_hz(case["topics"])
            hz.print_hz(case["topics"][:1])
        answers.append([reports, out.getvalue()])
    for case in request["bw"]:
        bw = rostopic.ROSTopicBandwidth(case["window"])
        out = io.StringIO()
        with redirect_stdout(out):
            for step, (at, size) in enumerate(case["arrivals"]):
                clock.now = at
                bw.callback(Raw(size))
                if step % 5 == 4:
                    clock.now = at + 0.25
                    bw.print_bw()
        answers.append(out.getvalue())
    answers.extend(_delays(request["delay"]))
    return answers


def _delays(cases: list[dict[str, Any]]) -> list[Any]:
    """ROSTopicDelay reads ROS time: set as /clock would, then back to the wall clock."""
    import rospy.rostime
    from geometry_msgs.msg import PointStamped
    from std_msgs.msg import String

    initialized = rospy.rostime.is_rostime_initialized()
    rospy.rostime.set_rostime_initialized(True)
    answers: list[Any] = []
    try:
        for case in cases:
            delay = rostopic.ROSTopicDelay(case["window"])
            out = io.StringIO()
            reports = []
            with redirect_stdout(out):
                delay.print_delay()  # nothing measured yet: prints nothing
                for step, (at, stamp) in enumerate(case["arrivals"]):
                    rospy.rostime._set_rostime(rospy.rostime.Time.from_sec(at))
                    msg: Any = String()  # no header (stamp -1): not counted
                    if stamp >= 0:
                        msg = PointStamped()
                        msg.header.stamp = rospy.rostime.Time.from_sec(stamp)
                    delay.callback_delay(msg)
                    if step % 6 == 2:
                        reports.append(repr(delay.get_delay()))
                    elif step % 6 == 5:
                        delay.print_delay()
                delay.print_delay()
                delay.print_delay()  # straight after a report: no new messages
            answers.append([reports, out.getvalue()])
    finally:
        rospy.rostime.switch_to_wallclock()
        rospy.rostime.set_rostime_initialized(initialized)
    return answers


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
