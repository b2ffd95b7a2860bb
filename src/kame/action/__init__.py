"""actionlib's rules as plain data: goal status codes, the server's goal-handle transitions,
cancel matching, the client's CommState machine, the simple client's state and goal ids.

Pure (L1): values in, values out; the `actionlib` compat package does the I/O and locking.
"""

from kame.action.cancel import CancelRequest, canceled_by_last_cancel
from kame.action.comm_state import (
    RESULT_ACCEPTED_IN,
    CommState,
    InvalidTransition,
    comm_steps,
    lost_when_unlisted,
)
from kame.action.goal_id import client_goal_id, generated_goal_id
from kame.action.server_goal import ServerEvent, server_transition
from kame.action.simple_state import SimpleGoalState, SimpleStep, simple_step
from kame.action.status import TERMINAL, Status

__all__ = [
    "RESULT_ACCEPTED_IN", "TERMINAL",
    "CancelRequest", "CommState", "InvalidTransition", "ServerEvent", "SimpleGoalState", "SimpleStep", "Status",
    "canceled_by_last_cancel", "client_goal_id", "comm_steps", "generated_goal_id", "lost_when_unlisted",
    "server_transition", "simple_step",
]
