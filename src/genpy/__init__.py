"""genpy, as ROS code imports it: the message base class, time values and errors, from kame."""

from genpy.message import struct_I
from genpy.rostime import Duration, Time, TVal
from kame.msg.errors import DeserializationError, SerializationError
from kame.msg.errors import MessageError as MessageException
from kame.msg.message import Message

__all__ = ["DeserializationError", "Duration", "Message", "MessageException", "SerializationError", "TVal", "Time",
           "struct_I"]
