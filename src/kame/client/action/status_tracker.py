"""StatusTracker: one goal's status on the server, and when it may leave the status list."""

from __future__ import annotations

from typing import Any

from actionlib_msgs.msg import GoalID, GoalStatus
from kame.client import clock
from kame.client.action.goal_id_generator import GoalIDGenerator


class StatusTracker:
    """For a received goal pass `goal`; for a cancel that came first, `goal_id` and `status`."""

    def __init__(self, goal_id: GoalID | None = None, status: int | None = None, goal: Any = None) -> None:
        self.goal = goal
        self.handle_tracker: Any = None
        self.status = GoalStatus()
        # Zero: stays listed. Otherwise the time the goal finished (or the stub was made);
        # the server drops it status_list_timeout later.
        self.handle_destruction_time = clock.Time()
        if goal_id is not None:
            self.status.goal_id = goal_id
            self.status.status = status if status is not None else GoalStatus.PENDING
            return
        self.status.goal_id = GoalID(stamp=goal.goal_id.stamp, id=goal.goal_id.id)
        self.status.status = GoalStatus.PENDING
        if self.status.goal_id.id == "":
            self.status.goal_id = GoalIDGenerator().generate_ID()
        if self.status.goal_id.stamp.is_zero():
            self.status.goal_id.stamp = clock.Time.now()
