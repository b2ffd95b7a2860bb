"""roslib.exceptions: roslib's base exception."""

__all__ = ["ROSLibException"]


class ROSLibException(Exception):
    """Base class of roslib's exceptions."""
