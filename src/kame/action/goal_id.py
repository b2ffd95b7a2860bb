"""Goal id strings as ROS makes them (spec §9.2); the caller supplies the counter and the time."""

from __future__ import annotations


def client_goal_id(caller_id: str, counter: int, secs: int, nsecs: int) -> str:
    """The Python ActionClient's form: `<caller_id>-<counter>-<secs with 3 decimals>`."""
    return f"{caller_id}-{counter}-{secs + nsecs * 1e-9:.3f}"


def generated_goal_id(name: str, counter: int, secs: int, nsecs: int) -> str:
    """GoalIDGenerator's (and C++'s) form, used by a server for goals sent without an id."""
    return f"{name}-{counter}-{secs}.{nsecs}"
