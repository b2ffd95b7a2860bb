"""actionlib.goal_id_generator: kame.client.action.goal_id_generator under actionlib's name."""

from kame.client.action.goal_id_generator import (
    GoalIDGenerator,
)

__all__ = [
    "GoalIDGenerator",
]
