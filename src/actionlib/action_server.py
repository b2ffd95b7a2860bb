"""actionlib.action_server: kame.client.action.action_server under actionlib's name."""

from kame.client.action.action_server import (
    ActionServer,
    action_types,
    nop_cb,
    queue_size_param,
)

__all__ = [
    "ActionServer",
    "action_types",
    "nop_cb",
    "queue_size_param",
]
