"""How publish(*args, **kwds) and a service call's arguments become a message, as in rospy."""

from __future__ import annotations

from typing import Any

from kame.msg.anymsg import AnyMsg
from kame.msg.message import Message


def args_kwds_to_message(data_class: type[Any], args: tuple[Any, ...], kwds: dict[str, Any]) -> Any:
    """What publish(*args, **kwds) and ServiceProxy(*args) build their message from."""
    if args and kwds:
        raise TypeError("publish() can be called with arguments or keywords, but not both.")
    if kwds:
        return data_class(**kwds)
    if len(args) == 1:
        arg = args[0]
        # the message itself (compared by md5sum: a dynamically made class is the same type), or any AnyMsg
        if getattr(arg, "_md5sum", None) == data_class._md5sum or isinstance(arg, AnyMsg):
            return arg
        if isinstance(arg, Message):
            # a message for the class's first field, as rospy takes it: proxy(config) builds Request(config)
            first = data_class._slot_types[0] if data_class._slot_types else ""
            if arg._type != first:
                raise TypeError(f"expected [{first}] but got [{arg._type}]")
    return data_class(*args)
