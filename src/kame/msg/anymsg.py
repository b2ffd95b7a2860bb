"""AnyMsg: a message of any type, kept as its serialized bytes (`_buff`).

What relays, recorders and tools that read topics of any type subscribe with: the
subscription asks for md5sum `*`, and each message stays the bytes the publisher sent until
someone builds a class for them (kame.msg.lookup.class_for, from the connection header).
"""

from __future__ import annotations

from typing import Any

from kame.msg.errors import MessageError, ROSException
from kame.msg.message import Message


class AnyMsg(Message):
    __slots__ = ("_buff",)
    _type = "*"
    _md5sum = "*"
    _full_text = ""
    _has_header = False
    _slot_types = ()

    def __init__(self, *args: Any) -> None:
        if args:
            raise MessageError("AnyMsg does not accept arguments")
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
