"""The client's exceptions, under rospy's names (ROSException, ROSInterruptException, ...)."""

from kame.msg.errors import DeserializationError, ROSException, SerializationError


class ROSSerializationException(ROSException):
    """Exception for message serialization errors."""


class ROSInitException(ROSException):
    """Exception for errors initializing ROS state."""


class InvalidCommandLineParams(ROSInitException):
    """A `_p:=value` argument that is not YAML (or an alias bomb): rospy's ROSInitException,
    which a program may catch; left uncaught it is one line on stderr, not a traceback
    (kame.client.process installs the hook)."""


class ROSInterruptException(ROSException, KeyboardInterrupt):
    """Raised when a wait is interrupted by shutdown (Ctrl-C, rospy.signal_shutdown)."""


class ROSTimeMovedBackwardsException(ROSInterruptException):
    """Raised by sleep() when ROS time moved backwards (simulated time was reset)."""

    def __init__(self, time: float) -> None:
        self.time = time
        super().__init__("ROS time moved backwards")


class ROSInternalException(Exception):
    """Base class for exceptions that are internal to the ROS system."""


class TransportException(ROSInternalException):
    pass


class TransportInitError(TransportException):
    pass


class TransportTerminated(TransportException):
    pass


__all__ = [
    "DeserializationError",
    "ROSException",
    "ROSInitException",
    "ROSInternalException",
    "ROSInterruptException",
    "ROSSerializationException",
    "ROSTimeMovedBackwardsException",
    "SerializationError",
    "TransportException",
    "TransportInitError",
    "TransportTerminated",
]
