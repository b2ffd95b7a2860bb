"""The errors of the message layer, one family per concern, each raised `from` its cause."""


class ROSException(Exception):
    """Base exception class for ROS clients (rospy.ROSException). It lives here, at the floor,
    because a message raises it too: an AnyMsg serialized before it holds any bytes, as rospy's."""


class MessageError(Exception):
    """Base of every error raised by kame.msg (genpy calls this MessageException)."""


class MsgDefinitionError(MessageError):
    """A .msg/.srv/.action text is malformed; the text says which file and line."""


class MsgNotFoundError(MessageError):
    """A type could not be located on the package path."""


class SerializationError(MessageError):
    """A message could not be written: a field has the wrong type or is out of range."""


class DeserializationError(MessageError):
    """Bytes could not be read as the expected message type (truncated or malformed)."""
