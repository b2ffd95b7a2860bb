"""Feeds message_filters a recorded sequence of stamped messages and prints what comes out.

Run by kame's interpreter and by Debian's /usr/bin/python3 (its real message_filters) on the
same JSON request, so the two outputs can be compared. Plain Python both interpreters run.
"""

from __future__ import annotations

import json
import sys
from typing import Any

import message_filters
import rospy
import rospy.rostime


class Header:
    def __init__(self, stamp: Any) -> None:
        self.stamp = stamp


class Stamped:
    def __init__(self, ident: int, secs: int, nsecs: int) -> None:
        self.ident = ident
        self.header = Header(rospy.Time(secs, nsecs))


def run(request: dict[str, Any]) -> dict[str, Any]:
    rospy.rostime.set_rostime_initialized(True)  # the filters read ROS time (the wall clock here)
    inputs = [message_filters.SimpleFilter() for _ in range(request["inputs"])]
    delivered: list[list[int]] = []
    kind = request["kind"]
    if kind == "exact":
        sync: Any = message_filters.TimeSynchronizer(inputs, request["queue_size"])
    elif kind == "approx":
        sync = message_filters.ApproximateTimeSynchronizer(inputs, request["queue_size"], request["slop"])
    else:
        sync = message_filters.Cache(inputs[0], request["queue_size"])
    sync.registerCallback(lambda *msgs: delivered.append([m.ident for m in msgs]))
    for ident, (index, secs, nsecs) in enumerate(request["events"]):
        inputs[index].signalMessage(Stamped(ident, secs, nsecs))
    answer: dict[str, Any] = {"delivered": delivered}
    if kind == "cache":
        def ident(msg: Any) -> int | None:
            return None if msg is None else int(msg.ident)

        queries = []
        for secs, nsecs, to_secs in request["queries"]:
            t = rospy.Time(secs, nsecs)
            queries.append([ident(sync.getElemAfterTime(t)), ident(sync.getElemBeforeTime(t)),
                            [m.ident for m in sync.getInterval(t, rospy.Time(to_secs, nsecs))]])
        latest, oldest = sync.getLatestTime(), sync.getOldestTime()
        answer["queries"] = queries
        answer["ends"] = [None if t is None else [t.secs, t.nsecs] for t in (latest, oldest)]
        answer["last"] = ident(sync.getLast())
    return answer


if __name__ == "__main__":
    print(json.dumps([run(request) for request in json.load(sys.stdin)]))
