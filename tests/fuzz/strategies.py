"""Hypothesis strategies for ROS values: a message of any type, XML-RPC values, headers."""

from __future__ import annotations

import importlib
from typing import Any

from hypothesis import settings
from hypothesis import strategies as st

from kame.msg import Message
from kame.msg.catalog import SHARE_DIR, MsgCatalog, find_packages
from kame.msg.spec import split_array
from kame.rostime import Duration, Time

CATALOG = MsgCatalog(find_packages([SHARE_DIR]))
ALL_MESSAGE_TYPES = [t for p in sorted(CATALOG.packages) for t in CATALOG.message_types(p)]

_INT_RANGES = {"int8": (-(2**7), 2**7 - 1), "byte": (-(2**7), 2**7 - 1), "uint8": (0, 2**8 - 1),
               "char": (0, 2**8 - 1), "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1),
               "int32": (-(2**31), 2**31 - 1), "uint32": (0, 2**32 - 1), "int64": (-(2**63), 2**63 - 1),
               "uint64": (0, 2**64 - 1)}
#: For a test run once per shipped type (about 180): a fifth of the profile's examples.
PER_TYPE = settings(max_examples=max(3, settings.default.max_examples // 5))
#: Text as ROS strings carry it (UTF-8: no lone surrogates).
TEXT = st.text(st.characters(exclude_categories=("Cs",)), max_size=12)


def message_class(type_name: str) -> type[Message]:
    package, short = type_name.split("/")
    cls: type[Message] = getattr(importlib.import_module(f"{package}.msg"), short)
    return cls


def field_values(slot_type: str, cls: type[Message], name: str) -> st.SearchStrategy[Any]:
    base, is_array, length = split_array(slot_type)
    if is_array:
        if base in ("uint8", "char"):
            return st.binary(min_size=length or 0, max_size=length if length is not None else 8)
        element = field_values(base, cls, name)
        most = 3 if base in _INT_RANGES or base in ("bool", "float32", "float64", "string") else 1
        return st.lists(element, min_size=length or 0, max_size=length if length is not None else most)
    if base in _INT_RANGES:
        low, high = _INT_RANGES[base]
        return st.integers(low, high)
    if base == "bool":
        return st.booleans()
    if base == "float32":
        return st.floats(width=32, allow_nan=False)
    if base == "float64":
        return st.floats(allow_nan=False)
    if base == "string":
        return TEXT
    if base == "time":
        return st.builds(Time, st.integers(0, 2**32 - 1), st.integers(0, 999_999_999))
    if base == "duration":
        return st.builds(Duration, st.integers(-(2**31), 2**31 - 1), st.integers(0, 999_999_999))
    return messages(cls._slot_classes[name])


def messages(cls: type[Message]) -> st.SearchStrategy[Message]:
    fields = {name: st.deferred(lambda slot=slot, name=name: field_values(slot, cls, name))
              for name, slot in zip(cls.__slots__, cls._slot_types, strict=False)}
    return st.fixed_dictionaries(fields).map(lambda values: cls(**values))


#: What XML-RPC carries both ways (strings without the characters XML 1.0 cannot hold).
XML_TEXT = st.text(st.characters(exclude_categories=("Cs", "Cc"), exclude_characters="\ufffe\uffff"),
                   max_size=12)
XMLRPC_VALUES: st.SearchStrategy[Any] = st.recursive(
    st.integers(-(2**31), 2**31 - 1) | st.booleans() | st.floats(allow_nan=False, allow_infinity=False)
    | XML_TEXT | st.binary(max_size=12),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(XML_TEXT, inner, max_size=4),
    max_leaves=12)
