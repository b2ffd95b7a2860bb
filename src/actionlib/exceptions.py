"""actionlib.exceptions: kame.client.action.exceptions under actionlib's name."""

from kame.client.action.exceptions import (
    ActionException,
)

__all__ = [
    "ActionException",
]
