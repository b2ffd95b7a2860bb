"""actionlib.server_goal_handle: kame.client.action.server_goal_handle under actionlib's name."""

from kame.client.action.server_goal_handle import (
    ServerGoalHandle,
)

__all__ = [
    "ServerGoalHandle",
]
