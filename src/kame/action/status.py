"""actionlib_msgs/GoalStatus codes. LOST is the client's own: no server ever sends it."""

from __future__ import annotations

from enum import IntEnum


class Status(IntEnum):
    PENDING = 0
    ACTIVE = 1
    PREEMPTED = 2
    SUCCEEDED = 3
    ABORTED = 4
    REJECTED = 5
    PREEMPTING = 6
    RECALLING = 7
    RECALLED = 8
    LOST = 9


TERMINAL = frozenset({Status.PREEMPTED, Status.SUCCEEDED, Status.ABORTED, Status.REJECTED, Status.RECALLED})
