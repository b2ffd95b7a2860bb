"""How publish(*args, **kwds) and a service call's arguments become a message, as in rospy."""

from __future__ import annotations

from typing import Any

from kame.msg.message import Message


def args_kwds_to_message(data_class: type[Any], args: tuple[Any, ...], kwds: dict[str, Any]) -> Any:
    """What publish(*args, **kwds) and ServiceProxy(*args) build their message from."""
    if args and kwds:
        raise TypeError("publish() can be called with arguments or keywords, but not both.")
    if kwds:
        return data_class(**kwds)
    if len(args) == 1:
        arg = args[0]
        if isinstance(arg, Message):
            if arg._type != data_class._type:
                # a message for the class's first field, as rospy takes it: proxy(config) builds Request(config)
                first = data_class._slot_types[0] if data_class._slot_types else ""
                if arg._type != first:
                    raise TypeError(f"expected [{first}] but got [{arg._type}]")
            elif len(data_class.__slots__) != 1 or not isinstance(arg, data_class):
                return arg
        return data_class(*args)
    return data_class(*args)
