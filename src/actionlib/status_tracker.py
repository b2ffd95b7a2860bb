"""actionlib.status_tracker: kame.client.action.status_tracker under actionlib's name."""

from kame.client.action.status_tracker import (
    StatusTracker,
)

__all__ = [
    "StatusTracker",
]
