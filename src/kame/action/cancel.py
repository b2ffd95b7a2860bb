"""Which goals a cancel message (an actionlib_msgs/GoalID) cancels (spec §9.2).

Rules: id '' and stamp 0 cancel everything; a matching id cancels that goal; a non-zero
stamp cancels every goal stamped at or before it; the rules combine. Stamps are nanoseconds.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class CancelRequest:
    id: str
    stamp_ns: int

    @property
    def cancels_everything(self) -> bool:
        return self.id == "" and self.stamp_ns == 0

    def matches(self, goal_id: str, goal_stamp_ns: int) -> bool:
        return (self.cancels_everything or self.id == goal_id
                or (self.stamp_ns != 0 and goal_stamp_ns <= self.stamp_ns))

    def remembers_unknown_id(self, known_ids: set[str] | frozenset[str]) -> bool:
        """A cancel naming a goal the server has not seen leaves a RECALLING entry for it."""
        return self.id != "" and self.id not in known_ids


def canceled_by_last_cancel(goal_stamp_ns: int, last_cancel_ns: int) -> bool:
    """An arriving goal stamped at or before the latest cancel stamp is canceled at once."""
    return goal_stamp_ns != 0 and goal_stamp_ns <= last_cancel_ns
