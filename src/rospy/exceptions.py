"""rospy.exceptions: rospy's exception classes (kame.client.errors)."""

from kame.client.errors import (
    ROSException,
    ROSInitException,
    ROSInternalException,
    ROSInterruptException,
    ROSSerializationException,
    ROSTimeMovedBackwardsException,
    TransportException,
    TransportInitError,
    TransportTerminated,
)

__all__ = [
    "ROSException",
    "ROSInitException",
    "ROSInternalException",
    "ROSInterruptException",
    "ROSSerializationException",
    "ROSTimeMovedBackwardsException",
    "TransportException",
    "TransportInitError",
    "TransportTerminated",
]
