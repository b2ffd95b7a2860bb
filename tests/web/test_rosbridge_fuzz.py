"""Properties of rosbridge's encodings over every shipped message type (tests/fuzz's strategies):
JSON of a message reads back to the same JSON, CBOR of it decodes, and any JSON value a client
may send for a type either fills a message or is a ConversionError, never another exception."""

from __future__ import annotations

import json
from typing import Any

import cbor2
import pytest
from hypothesis import given
from hypothesis import strategies as st

from kame.rosbridge import conversion, protocol
from tests.fuzz.strategies import ALL_MESSAGE_TYPES, PER_TYPE, message_class, messages

JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers(-(2**70), 2**70) | st.floats(allow_nan=False) | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
    max_leaves=12)


@pytest.mark.parametrize("type_name", ALL_MESSAGE_TYPES)
@PER_TYPE
@given(data=st.data())
def test_json_reads_back_to_itself_and_cbor_decodes(type_name: str, data: st.DataObject) -> None:
    cls = message_class(type_name)
    msg = data.draw(messages(cls))
    sent = json.loads(protocol.encode_json({"op": "publish", "msg": conversion.to_json(msg)}))["msg"]
    assert conversion.to_json(conversion.from_json(cls, sent)) == sent
    decoded = cbor2.loads(protocol.encode_cbor(conversion.to_cbor_value(msg, protocol.cbor_tag)))
    assert sorted(decoded) == sorted(cls.__slots__)


@pytest.mark.parametrize("type_name", ALL_MESSAGE_TYPES)
@PER_TYPE
@given(value=st.dictionaries(st.text(max_size=8), JSON_VALUES, max_size=4) | JSON_VALUES)
def test_any_json_fills_a_message_or_says_why(type_name: str, value: Any) -> None:
    cls = message_class(type_name)
    try:
        filled = conversion.from_json(cls, value)
    except conversion.ConversionError:
        return
    assert isinstance(filled, cls)
