"""genpy.message: the message base class, str() formatting, and message classes by type name."""

from kame.msg.errors import DeserializationError, SerializationError
from kame.msg.errors import MessageError as MessageException
from kame.msg.message import Message, strify_message
from roslib.message import get_message_class, get_service_class

__all__ = ["DeserializationError", "Message", "MessageException", "SerializationError", "get_message_class",
           "get_service_class", "strify_message"]
