"""The SimpleActionClient's view of a goal: PENDING, ACTIVE or DONE, from CommState changes.

Rules: ACTIVE or PREEMPTING on a PENDING goal make it ACTIVE (active callback); DONE on a
PENDING or ACTIVE goal makes it DONE (done callback); anything else arriving on a DONE goal,
and RECALLING on a non-PENDING goal, is a protocol error to log.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

from kame.action.comm_state import CommState


class SimpleGoalState(IntEnum):
    PENDING = 0
    ACTIVE = 1
    DONE = 2


@dataclass(frozen=True)
class SimpleStep:
    state: SimpleGoalState
    call_active: bool = False
    call_done: bool = False
    error: str = ""


def simple_step(simple: SimpleGoalState, comm: CommState) -> SimpleStep:
    error = f"Received comm state {comm.name} when in simple state {simple.name}"
    if comm in (CommState.ACTIVE, CommState.PREEMPTING):
        if simple is SimpleGoalState.PENDING:
            return SimpleStep(SimpleGoalState.ACTIVE, call_active=True)
        if simple is SimpleGoalState.DONE:
            return SimpleStep(simple, error=error)
    elif comm is CommState.RECALLING:
        if simple is not SimpleGoalState.PENDING:
            return SimpleStep(simple, error=error)
    elif comm is CommState.DONE:
        if simple is SimpleGoalState.DONE:
            return SimpleStep(simple, error="SimpleActionClient received DONE twice")
        return SimpleStep(SimpleGoalState.DONE, call_done=True)
    return SimpleStep(simple)
