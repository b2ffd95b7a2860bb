"""genpy.dynamic: message classes built at run time from a message_definition text."""

from kame.msg.loader import generate_dynamic

__all__ = ["generate_dynamic"]
