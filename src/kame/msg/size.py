"""How large a serialized message can be, from its full definition (a connection header's
`message_definition`): exactly one size when no field has a variable length (no string, no
unbounded array, none below), else no bound. A subscriber limits its frames to that size, so
a peer cannot make it buffer more than the message can hold.
Pure: text in, a number out.
"""

from __future__ import annotations

import functools

from kame.msg.errors import MsgDefinitionError

__all__ = ["fixed_size"]

_SIZES = {
    "bool": 1, "byte": 1, "char": 1, "int8": 1, "uint8": 1, "int16": 2, "uint16": 2, "int32": 4, "uint32": 4,
    "float32": 4, "int64": 8, "uint64": 8, "float64": 8, "time": 8, "duration": 8,
}


@functools.lru_cache(maxsize=256)  # a node subscribes to many topics of a few types
def fixed_size(type_name: str, full_definition: str) -> int | None:
    """The serialized size every message of `type_name` has, or None when it varies (or the
    definition cannot say: empty, unparsable, a dependency missing)."""
    if not full_definition.strip() or _declares_variable_field(full_definition):
        return None
    # here, not at the top: the parser (with dataclasses, inspect, hashlib) is a few megabytes
    # that a node which only publishes never needs; the transport imports this module
    from kame.msg.md5 import split_full_text
    from kame.msg.parser import parse_msg

    main, deps = split_full_text(full_definition)
    texts = {**deps, type_name: main}
    sizes: dict[str, int | None] = {}

    def size_of(name: str, seen: tuple[str, ...]) -> int | None:
        if name in _SIZES:
            return _SIZES[name]
        if name in sizes:
            return sizes[name]
        text = texts.get(name)
        if text is None or name in seen:
            return None
        try:
            spec = parse_msg(text, name)
        except MsgDefinitionError:
            return None
        total: int | None = 0
        for field in spec.fields:
            if field.is_array and field.array_len is None:
                total = None
                break
            element = size_of(field.base_type, (*seen, name))
            if element is None or total is None:
                total = None
                break
            total += element * (field.array_len if field.is_array and field.array_len is not None else 1)
        sizes[name] = total
        return total

    return size_of(type_name, ())


def _declares_variable_field(full_definition: str) -> bool:
    """Whether a field of any section is a string or an unbounded array: the usual answer
    (any message with a Header), found without the parser. A full definition holds only the
    types its fields use, so such a field anywhere makes the size vary. Constants, comments,
    the sections' ===== lines and their MSG: lines declare no field."""
    for line in full_definition.splitlines():
        line = line.split("#", 1)[0]
        if "=" in line:
            continue
        words = line.split(None, 1)
        if words and (words[0] == "string" or words[0].endswith("[]")):
            return True
    return False
