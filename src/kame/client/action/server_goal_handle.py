"""ServerGoalHandle: the user's grip on one goal of an ActionServer.

Transitions follow kame.action.server_transition; a refused one is logged and changes nothing.
"""

from __future__ import annotations

from contextlib import AbstractContextManager
from typing import TYPE_CHECKING, Any, Protocol

from actionlib_msgs.msg import GoalID, GoalStatus
from kame.action import TERMINAL, ServerEvent, Status, server_transition
from kame.client import clock
from kame.client.action._log import logerr

if TYPE_CHECKING:
    from kame.client.action.status_tracker import StatusTracker

_REFUSED = {
    ServerEvent.ACCEPT: "To transition to an active state, the goal must be in a pending or recalling state",
    ServerEvent.REJECT: "To transition to a rejected state, the goal must be in a pending or recalling state",
    ServerEvent.CANCEL: "To transition to a cancelled state, the goal must be in a pending, recalling, active, "
                        "or preempting state",
    ServerEvent.SUCCEED: "To transition to a succeeded state, the goal must be in a preempting or active state",
    ServerEvent.ABORT: "To transition to an aborted state, the goal must be in a preempting or active state",
}


class GoalsServer(Protocol):
    """What a goal handle asks of the ActionServer (kame.client.action.action_server) it came from."""

    @property
    def lock(self) -> AbstractContextManager[Any]: ...

    @property
    def ActionResultType(self) -> Any: ...  # actionlib's name

    def publish_result(self, status: GoalStatus, result: Any) -> None: ...

    def publish_feedback(self, status: GoalStatus, feedback: Any) -> None: ...

    def publish_status(self) -> None: ...


class ServerGoalHandle:
    def __init__(self, status_tracker: StatusTracker | None = None, action_server: GoalsServer | None = None,
                 handle_tracker: Any = None) -> None:
        self.status_tracker = status_tracker
        self.action_server = action_server
        self.handle_tracker = handle_tracker
        self.goal = status_tracker.goal if status_tracker is not None else None

    def get_default_result(self) -> Any:
        assert self.action_server is not None
        return self.action_server.ActionResultType()

    def _apply(self, event: ServerEvent, result: Any = None, text: str = "") -> bool:
        """Apply `event`; publish the result (terminal) or the status. False when refused."""
        if not self.goal or self.status_tracker is None or self.action_server is None:
            logerr("Attempt to set status on an uninitialized ServerGoalHandle")
            return False
        server = self.action_server
        with server.lock:
            status = self.status_tracker.status
            after = server_transition(status.status, event)
            if after is None:
                if event in _REFUSED:
                    logerr("%s, it is currently in state: %d", _REFUSED[event], status.status)
                return False
            status.status = int(after)
            if event is not ServerEvent.CANCEL_REQUEST:
                status.text = text
            if after in TERMINAL:
                self.status_tracker.handle_destruction_time = clock.Time.now()
                server.publish_result(status, result if result is not None else self.get_default_result())
            else:
                server.publish_status()
            return True

    def set_accepted(self, text: str = "") -> None:
        self._apply(ServerEvent.ACCEPT, text=text)

    def set_canceled(self, result: Any = None, text: str = "") -> None:
        self._apply(ServerEvent.CANCEL, result, text)

    def set_rejected(self, result: Any = None, text: str = "") -> None:
        self._apply(ServerEvent.REJECT, result, text)

    def set_aborted(self, result: Any = None, text: str = "") -> None:
        self._apply(ServerEvent.ABORT, result, text)

    def set_succeeded(self, result: Any = None, text: str = "") -> None:
        self._apply(ServerEvent.SUCCEED, result, text)

    def set_cancel_requested(self) -> bool:
        """PENDING -> RECALLING or ACTIVE -> PREEMPTING; True when the user should hear of it."""
        if not self.goal:
            return False
        return self._apply(ServerEvent.CANCEL_REQUEST)

    def publish_feedback(self, feedback: Any) -> None:
        if not self.goal or self.status_tracker is None or self.action_server is None:
            logerr("Attempt to publish feedback on an uninitialized ServerGoalHandle")
            return
        with self.action_server.lock:
            self.action_server.publish_feedback(self.status_tracker.status, feedback)

    def get_goal(self) -> Any:
        return self.goal.goal if self.goal else None

    def get_goal_id(self) -> GoalID:
        if not self.goal or self.status_tracker is None:
            logerr("Attempt to get a goal id on an uninitialized ServerGoalHandle")
            return GoalID()
        return self.status_tracker.status.goal_id

    def get_goal_status(self) -> GoalStatus:
        if not self.goal or self.status_tracker is None:
            logerr("Attempt to get goal status on an uninitialized ServerGoalHandle")
            return GoalStatus()
        return self.status_tracker.status

    def _id(self) -> str | None:
        return self.status_tracker.status.goal_id.id if self.goal and self.status_tracker is not None else None

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ServerGoalHandle):
            return False
        mine = self._id()
        return mine is not None and mine == other._id()

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __hash__(self) -> int:
        return hash(self._id())

    def __repr__(self) -> str:
        if not self.goal or self.status_tracker is None:
            return "<ServerGoalHandle (empty)>"
        status = self.status_tracker.status
        return f"<ServerGoalHandle {status.goal_id.id} {Status(status.status).name}>"
