"""actionlib.simple_action_client: kame.client.action.simple_action_client under actionlib's name."""

from kame.client.action.simple_action_client import (
    SimpleActionClient,
    SimpleGoalState,
)

__all__ = [
    "SimpleActionClient",
    "SimpleGoalState",
]
