"""The server's goal-handle state machine (spec §9.3).

Rules: a transition not in the table is refused (the caller logs it, the status stays).
A transition into a terminal status publishes one result; any other publishes the status.
"""

from __future__ import annotations

from enum import Enum

from kame.action.status import Status


class ServerEvent(Enum):
    ACCEPT = "accept"
    REJECT = "reject"
    CANCEL_REQUEST = "cancel request"  # from the cancel topic
    CANCEL = "set canceled"
    SUCCEED = "succeed"
    ABORT = "abort"


_TABLE: dict[ServerEvent, dict[Status, Status]] = {
    ServerEvent.ACCEPT: {Status.PENDING: Status.ACTIVE, Status.RECALLING: Status.PREEMPTING},
    ServerEvent.REJECT: {Status.PENDING: Status.REJECTED, Status.RECALLING: Status.REJECTED},
    ServerEvent.CANCEL_REQUEST: {Status.PENDING: Status.RECALLING, Status.ACTIVE: Status.PREEMPTING},
    ServerEvent.CANCEL: {Status.PENDING: Status.RECALLED, Status.RECALLING: Status.RECALLED,
                         Status.ACTIVE: Status.PREEMPTED, Status.PREEMPTING: Status.PREEMPTED},
    ServerEvent.SUCCEED: {Status.ACTIVE: Status.SUCCEEDED, Status.PREEMPTING: Status.SUCCEEDED},
    ServerEvent.ABORT: {Status.ACTIVE: Status.ABORTED, Status.PREEMPTING: Status.ABORTED},
}


def server_transition(status: int, event: ServerEvent) -> Status | None:
    """The status after `event` on a goal in `status`, or None when the event is not allowed there."""
    try:
        return _TABLE[event].get(Status(status))
    except ValueError:
        return None
