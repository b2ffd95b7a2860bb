"""genpy.dynamic: message classes built at run time from a message_definition text (kame's
loader compiles them with kame's codegen, as it does for a bag's or a connection's types)."""

from io import StringIO as StringIO  # genpy.dynamic's name, imported from it by old code

from genmsg import MsgContext, MsgGenerationException
from genpy.generator import msg_generator
from kame.msg.loader import generate_dynamic

__all__ = ["MsgContext", "MsgGenerationException", "generate_dynamic", "msg_generator"]
