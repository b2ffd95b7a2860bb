"""The one error class of kame.gazebo: what the simulator refuses, and why, in the words a user needs."""

from __future__ import annotations


class GazeboError(ValueError):
    """A world, model or request the simulator refuses; the text names the file or element and says why."""
