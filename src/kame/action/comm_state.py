"""The action client's CommState machine (spec §9.4), driven by the status of its goal.

Rules: each status array moves a goal through the states listed for (state, status) in
order (skipped intermediate states are passed through); () is no transition; a missing
entry is an invalid transition (the server broke the protocol: logged, state kept).
A goal missing from a status array is LOST unless it waits for its ack or its result.
"""

from __future__ import annotations

from enum import IntEnum

from kame.action.status import Status


class CommState(IntEnum):
    WAITING_FOR_GOAL_ACK = 0
    PENDING = 1
    ACTIVE = 2
    WAITING_FOR_RESULT = 3
    WAITING_FOR_CANCEL_ACK = 4
    RECALLING = 5
    PREEMPTING = 6
    DONE = 7
    LOST = 8


class InvalidTransition(Exception):
    def __init__(self, state: CommState, status: Status) -> None:
        super().__init__(f"Invalid goal status transition from {state.name} to {status.name}")
        self.state = state
        self.status = status


_C = CommState
_S = Status
_WFR = _C.WAITING_FOR_RESULT

_TABLE: dict[CommState, dict[Status, tuple[CommState, ...]]] = {
    _C.WAITING_FOR_GOAL_ACK: {
        _S.PENDING: (_C.PENDING,), _S.ACTIVE: (_C.ACTIVE,),
        _S.REJECTED: (_C.PENDING, _WFR), _S.RECALLING: (_C.PENDING, _C.RECALLING),
        _S.RECALLED: (_C.PENDING, _WFR), _S.PREEMPTED: (_C.ACTIVE, _C.PREEMPTING, _WFR),
        _S.SUCCEEDED: (_C.ACTIVE, _WFR), _S.ABORTED: (_C.ACTIVE, _WFR),
        _S.PREEMPTING: (_C.ACTIVE, _C.PREEMPTING)},
    _C.PENDING: {
        _S.PENDING: (), _S.ACTIVE: (_C.ACTIVE,), _S.REJECTED: (_WFR,), _S.RECALLING: (_C.RECALLING,),
        _S.RECALLED: (_C.RECALLING, _WFR), _S.PREEMPTED: (_C.ACTIVE, _C.PREEMPTING, _WFR),
        _S.SUCCEEDED: (_C.ACTIVE, _WFR), _S.ABORTED: (_C.ACTIVE, _WFR),
        _S.PREEMPTING: (_C.ACTIVE, _C.PREEMPTING)},
    _C.ACTIVE: {
        _S.ACTIVE: (), _S.PREEMPTED: (_C.PREEMPTING, _WFR), _S.SUCCEEDED: (_WFR,), _S.ABORTED: (_WFR,),
        _S.PREEMPTING: (_C.PREEMPTING,)},
    _C.WAITING_FOR_RESULT: {
        _S.ACTIVE: (), _S.REJECTED: (), _S.RECALLED: (), _S.PREEMPTED: (), _S.SUCCEEDED: (), _S.ABORTED: ()},
    _C.WAITING_FOR_CANCEL_ACK: {
        _S.PENDING: (), _S.ACTIVE: (), _S.REJECTED: (_WFR,), _S.RECALLING: (_C.RECALLING,),
        _S.RECALLED: (_C.RECALLING, _WFR), _S.PREEMPTED: (_C.PREEMPTING, _WFR),
        _S.SUCCEEDED: (_C.PREEMPTING, _WFR), _S.ABORTED: (_C.PREEMPTING, _WFR),
        _S.PREEMPTING: (_C.PREEMPTING,)},
    _C.RECALLING: {
        _S.REJECTED: (_WFR,), _S.RECALLING: (), _S.RECALLED: (_WFR,), _S.PREEMPTED: (_C.PREEMPTING, _WFR),
        _S.SUCCEEDED: (_C.PREEMPTING, _WFR), _S.ABORTED: (_C.PREEMPTING, _WFR),
        _S.PREEMPTING: (_C.PREEMPTING,)},
    _C.PREEMPTING: {
        _S.PREEMPTED: (_WFR,), _S.SUCCEEDED: (_WFR,), _S.ABORTED: (_WFR,), _S.PREEMPTING: ()},
    _C.DONE: {
        _S.REJECTED: (), _S.RECALLED: (), _S.PREEMPTED: (), _S.SUCCEEDED: (), _S.ABORTED: ()},
}

# A result is taken (and the goal moves to DONE) in any state but DONE itself.
RESULT_ACCEPTED_IN = frozenset(set(CommState) - {CommState.DONE, CommState.LOST})


def comm_steps(state: CommState, status: int) -> tuple[CommState, ...]:
    """The states a goal in `state` passes through on seeing `status`; InvalidTransition if none may.

    ValueError for a status code that is not a GoalStatus (LOST included: no server sends it).
    """
    code = Status(status)
    if code is Status.LOST:
        raise ValueError("LOST is not a status a server sends")
    steps = _TABLE[state].get(code)
    if steps is None:
        raise InvalidTransition(state, code)
    return steps


def lost_when_unlisted(state: CommState) -> bool:
    """A status array without the goal's id makes the goal LOST in this state."""
    return state not in (CommState.WAITING_FOR_GOAL_ACK, CommState.WAITING_FOR_RESULT, CommState.DONE)
