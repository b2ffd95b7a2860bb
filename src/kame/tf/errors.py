"""tf2's exceptions (tf2_ros re-exports them): the class tells the kind, the text is tf2's."""

from __future__ import annotations


class TransformException(Exception):
    pass


class ConnectivityException(TransformException):
    """The two frames are not in one tree, or the tree has a loop."""


class LookupException(TransformException):
    """A frame does not exist."""


class ExtrapolationException(TransformException):
    """The time asked for is outside the data the buffer holds."""


class InvalidArgumentException(TransformException):
    """An empty or '/'-prefixed frame id, or a transform with NaNs."""


class TimeoutException(TransformException):
    """A wait for a transform ended before it could be done."""
