"""actionlib.simple_action_server: kame.client.action.simple_action_server under actionlib's name."""

from kame.client.action.simple_action_server import (
    SimpleActionServer,
)

__all__ = [
    "SimpleActionServer",
]
