"""Properties of the message layer: every shipped type round-trips any value, no byte string
makes deserialization do anything but return a message or raise DeserializationError, the IDL
parser refuses what it cannot read with MsgDefinitionError, and rostopic pub's argument filling
raises FillError (not a crash) on arguments that do not fit."""

from __future__ import annotations

import io

import pytest
from hypothesis import given
from hypothesis import strategies as st

from kame.msg import DeserializationError, Message, MessageError
from kame.msg.fill import FillError, fill_message_args
from kame.msg.message import find_type_problem
from kame.msg.parser import parse_msg, parse_srv

from .strategies import ALL_MESSAGE_TYPES, PER_TYPE, message_class, messages


def serialize(msg: Message) -> bytes:
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


@pytest.mark.parametrize("type_name", ALL_MESSAGE_TYPES)
@PER_TYPE
@given(data=st.data())
def test_every_shipped_type_round_trips_any_value(type_name: str, data: st.DataObject) -> None:
    cls = message_class(type_name)
    msg = data.draw(messages(cls))
    wire = serialize(msg)
    back = cls().deserialize(wire)
    assert back == msg
    assert serialize(back) == wire


@pytest.mark.parametrize("type_name", ALL_MESSAGE_TYPES)
@PER_TYPE
@given(junk=st.binary(max_size=64))
def test_no_byte_string_makes_deserialization_crash(type_name: str, junk: bytes) -> None:
    try:
        message_class(type_name)().deserialize(junk)
    except DeserializationError:
        pass


_FIELD_TYPES = st.sampled_from(["int8", "uint32", "float64", "string", "time", "bool[]", "uint8[4]",
                                "Header", "geometry_msgs/Point", "string[2]", "duration[]"])
_NAMES = st.from_regex(r"[a-z][a-z0-9_]{0,6}", fullmatch=True)


@given(fields=st.lists(st.tuples(_FIELD_TYPES, _NAMES), max_size=6, unique_by=lambda f: f[1]))
def test_valid_definitions_parse_to_their_fields(fields: list[tuple[str, str]]) -> None:
    text = "".join(f"{t} {n}  # comment\n" for t, n in fields)
    spec = parse_msg(text, "pkg/Msg")
    assert spec.names == tuple(n for _, n in fields)


@given(text=st.text(max_size=80))
def test_any_text_parses_or_is_a_definition_error(text: str) -> None:
    for parse in (parse_msg, parse_srv):
        try:
            parse(text, "pkg/Thing")
        except MessageError:
            pass


_YAMLISH = st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
                        lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=6), inner,
                                                                                   max_size=3),
                        max_leaves=8)


@pytest.mark.parametrize("type_name", ["geometry_msgs/Twist", "std_msgs/Header", "sensor_msgs/JointState",
                                       "std_msgs/String", "visualization_msgs/Marker"])
@given(args=st.lists(_YAMLISH, max_size=3))
def test_rostopic_pub_arguments_fill_or_say_why(type_name: str, args: list[object]) -> None:
    msg = message_class(type_name)()
    try:
        fill_message_args(msg, args)
    except FillError:
        return
    if find_type_problem(msg) is None:  # what rostopic checks (and reports) before sending
        serialize(msg)
