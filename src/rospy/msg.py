"""rospy.msg: AnyMsg and the helpers for building messages from arguments."""

from __future__ import annotations

from typing import Any

from kame.msg.message import Message
from rospy.exceptions import ROSException


class AnyMsg(Message):
    """A message of any type, kept as its serialized bytes (`_buff`): for relays and recorders."""

    __slots__ = ("_buff",)
    _type = "*"
    _md5sum = "*"
    _full_text = ""
    _has_header = False
    _slot_types = ()

    def __init__(self, *args: Any) -> None:
        if args:
            raise ROSException("AnyMsg does not accept arguments")
        self._buff: bytes | None = None

    def serialize(self, buff: Any) -> None:
        if self._buff is None:
            raise ROSException("AnyMsg is not initialized")
        buff.write(self._buff)

    def deserialize(self, data: Any) -> AnyMsg:
        self._buff = bytes(data)
        return self

    @classmethod
    def _from_buffer(cls, data: Any) -> AnyMsg:
        return cls().deserialize(data)


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
                raise TypeError(f"expected [{data_class._type}] but got [{arg._type}]")
            if len(data_class.__slots__) != 1 or not isinstance(arg, data_class):
                return arg
        return data_class(*args)
    return data_class(*args)
