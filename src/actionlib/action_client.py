"""actionlib.action_client: kame.client.action.action_client under actionlib's name."""

from kame.client.action.action_client import (
    ActionClient,
    ClientGoalHandle,
    CommState,
    CommStateMachine,
    GoalManager,
    TerminalState,
    get_name_of_constant,
)

__all__ = [
    "ActionClient",
    "ClientGoalHandle",
    "CommState",
    "CommStateMachine",
    "GoalManager",
    "TerminalState",
    "get_name_of_constant",
]
