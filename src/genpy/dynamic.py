"""genpy.dynamic: message classes built at run time from a message_definition text (kame's
loader compiles them with kame's codegen, as it does for a bag's or a connection's types)."""

from genmsg import MsgContext, MsgGenerationException
from genpy.generator import msg_generator
from kame.msg.loader import generate_dynamic

__all__ = ["MsgContext", "MsgGenerationException", "generate_dynamic", "msg_generator"]
