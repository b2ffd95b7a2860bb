"""Generated message classes behave like genpy's and every shipped type round-trips."""

from __future__ import annotations

import importlib
import io
import pickle
import struct
from typing import Any

import numpy
import pytest

from kame.msg import DeserializationError, Message, MsgCatalog, SerializationError
from kame.msg.catalog import SHARE_DIR, find_packages
from kame.rostime import Time

from .values import filled

CATALOG = MsgCatalog(find_packages([SHARE_DIR]))
ALL_MESSAGE_TYPES = [t for p in sorted(CATALOG.packages) for t in CATALOG.message_types(p)]
ALL_SERVICE_TYPES = [t for p in sorted(CATALOG.packages) for t in CATALOG.service_types(p)]


def message_class(type_name: str) -> type[Message]:
    package, short = type_name.split("/")
    cls: type[Message] = getattr(importlib.import_module(f"{package}.msg"), short)
    return cls


def serialize(msg: Message) -> bytes:
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


@pytest.mark.parametrize("type_name", ALL_MESSAGE_TYPES)
def test_every_shipped_message_round_trips(type_name: str) -> None:
    cls = message_class(type_name)
    assert cls._type == type_name
    assert cls._md5sum == CATALOG.md5sum(type_name)
    assert cls._full_text == CATALOG.full_text(type_name)
    for msg in (cls(), filled(cls)):
        data = serialize(msg)
        back = cls().deserialize(data)
        assert back == msg
        assert serialize(back) == data
        assert cls().deserialize_numpy(data, numpy) == back
        assert pickle.loads(pickle.dumps(msg)) == msg


def test_fixed_size_is_the_size_of_every_message_of_a_fixed_size_type() -> None:
    # A subscriber refuses frames longer than this: it must be exact, and None when sizes vary.
    from kame.msg.size import fixed_size

    fixed = 0
    for type_name in ALL_MESSAGE_TYPES:
        cls = message_class(type_name)
        size = fixed_size(type_name, cls._full_text)
        sizes = {len(serialize(cls())), len(serialize(filled(cls)))}
        if size is None:  # an empty definition says nothing (a caller without one passes "")
            assert not cls._full_text or any(word in cls._full_text for word in ("string", "[]")), type_name
        else:
            fixed += 1
            assert sizes == {size}, type_name
    assert fixed > 20


def test_fixed_size_finds_variable_sizes_without_the_parser_as_the_parser_does(monkeypatch: pytest.MonkeyPatch) -> None:
    # the quick scan (a string or an unbounded array declared anywhere) never says "varies"
    # where the parser finds a fixed size
    from kame.msg import size

    quick = {name: size._declares_variable_field(message_class(name)._full_text) for name in ALL_MESSAGE_TYPES}
    monkeypatch.setattr(size, "_declares_variable_field", lambda text: False)
    parsed = {name: size.fixed_size.__wrapped__(name, message_class(name)._full_text) for name in ALL_MESSAGE_TYPES}
    assert [name for name, varies in quick.items() if varies and parsed[name] is not None] == []
    assert sum(quick.values()) > 100
    assert size._declares_variable_field('string FOO=a # b\nint32 X=1\nfloat64 x # = []\n') is False


@pytest.mark.parametrize("type_name", ALL_SERVICE_TYPES)
def test_every_shipped_service_round_trips(type_name: str) -> None:
    package, short = type_name.split("/")
    module = importlib.import_module(f"{package}.srv")
    srv = getattr(module, short)
    assert srv._md5sum == CATALOG.srv_md5sum(type_name)
    assert srv._request_class is getattr(module, short + "Request")
    assert srv._response_class is getattr(module, short + "Response")
    for cls in (srv._request_class, srv._response_class):
        msg = filled(cls)
        assert cls().deserialize(serialize(msg)) == msg


def test_constructor_rules() -> None:
    from geometry_msgs.msg import Point, Twist, Vector3

    assert Point(1.0, 2.0, 3.0) == Point(x=1.0, y=2.0, z=3.0)
    assert (Point(y=2.0).x, Point(y=2.0).y) == (0.0, 2.0)
    twist = Twist(linear=Vector3(1, 0, 0))
    assert twist.angular == Vector3()
    with pytest.raises(TypeError, match="args OR keywords"):
        Point(1.0, y=2.0)
    with pytest.raises(TypeError, match="Invalid number of arguments"):
        Point(1.0, 2.0)
    with pytest.raises(AttributeError, match="nope is not an attribute of Point"):
        Point(nope=1)
    with pytest.raises(AttributeError):
        Point().nope = 1  # type: ignore[attr-defined]


def test_class_attributes_and_constants() -> None:
    from rosgraph_msgs.msg import Log
    from sensor_msgs.msg import Image

    assert Log.__slots__ == ("header", "level", "name", "msg", "file", "function", "line", "topics")
    assert Log._slot_types == ("std_msgs/Header", "byte", "string", "string", "string", "string", "uint32",
                               "string[]")
    assert (Log.DEBUG, Log.INFO, Log.WARN, Log.ERROR, Log.FATAL) == (1, 2, 4, 8, 16)
    assert Log._has_header and Image._has_header
    assert Image().data == b""
    assert Image()._get_types() == Image._slot_types


def test_defaults_follow_genpy() -> None:
    from geometry_msgs.msg import PoseWithCovariance
    from std_msgs.msg import Bool, Header, String

    assert Bool().data is False
    assert String().data == ""
    assert Header().stamp == Time(0, 0)
    covariance = PoseWithCovariance().covariance
    assert covariance == [0.0] * 36


def test_arrays_are_lists_in_and_tuples_out() -> None:
    from sensor_msgs.msg import JointState

    msg = JointState(name=["a"], position=[1.0])
    back = JointState().deserialize(serialize(msg))
    assert back.position == (1.0,)
    assert back.name == ["a"]
    assert back == msg  # lists and tuples compare equal, as genpy does


def test_numeric_arrays_of_any_length_and_kind_keep_their_bytes() -> None:
    # Lists and tuples go through structs cached per element count; counts past the cache's
    # bound and array-like values take other paths: the bytes must not depend on which.
    import array

    from kame.msg.runtime import ArrayStructs
    from sensor_msgs.msg import JointState

    for count in (0, 1, 6, ArrayStructs.MAX_CACHED + 1):
        values = [0.5 * i for i in range(count)]
        expected = struct.pack(f"<I{count}d", count, *values)
        for value in (values, tuple(values), numpy.array(values), array.array("d", values)):
            data = serialize(JointState(position=value))
            assert data[-8 - len(expected):-8] == expected  # then velocity, effort: 4-byte zero counts
            assert JointState().deserialize(data).position == tuple(values)
    counted = ArrayStructs("<%dd")
    for count in (3, ArrayStructs.MAX_CACHED + 1, 1 << 28):
        assert counted[count].size == 8 * count
    assert sorted(counted) == [3]  # only small counts are kept: bad input cannot grow the cache


def test_wire_structs_write_and_read_the_little_endian_bytes() -> None:
    # Generated code may get a native struct (faster for float64): it must be byte for byte
    # and error for error the "<" one, and only formats without padding, float32 or bool qualify.
    from kame.msg.runtime import NATIVE_IS_WIRE, wire_struct

    specials = [0.0, -0.0, 1.5, -2.25e300, 5e-324, float("inf"), float("-inf"), float("nan")]
    for fmt, values in [("<8d", specials), ("<IIIId", [1, 2**32 - 1, 0, 7, -1.5]),
                        ("<dqQ", [3.0, -(2**63), 2**64 - 1]), ("<Id", [9, 0.25]), ("<ff", [1.5, -2.0]),
                        ("<d?", [1.0, True]), ("<I", [5])]:
        compiled, standard = wire_struct(fmt), struct.Struct(fmt)
        data = standard.pack(*values)
        assert compiled.size == standard.size and compiled.pack(*values) == data
        assert repr(compiled.unpack_from(data, 0)) == repr(standard.unpack_from(data, 0))
    assert wire_struct("<8d").format == ("@8d" if NATIVE_IS_WIRE else "<8d")
    for kept in ("<Id", "<ff", "<d?", "<I"):  # padding, float32 overflow, C _Bool, nothing to gain
        assert wire_struct(kept).format == kept
    for fmt, bad in [("<dI", (1.0, 2**32)), ("<dQ", (1.0, -1)), ("<dd", (1.0, "x"))]:
        with pytest.raises(struct.error):
            wire_struct(fmt).pack(*bad)


def test_strings_decode_alike_from_every_kind_of_buffer() -> None:
    # deserialize decodes strings with bytes.decode and hands other buffers to _from_buffer:
    # the same fields either way, invalid UTF-8 replaced as str(b, "utf-8", "replace") does.
    from sensor_msgs.msg import JointState

    msg = JointState(name=["\u00e9lbow", "wrist"], position=[1.0, 2.0])
    msg.header.frame_id = "base"
    data = serialize(msg).replace(b"wrist", b"wr\xffst")
    for buffer in (data, bytearray(data), memoryview(data)):
        for back in (JointState().deserialize(buffer), JointState._from_buffer(buffer)):
            assert back.name == ["\u00e9lbow", "wr\ufffdst"] and back.header.frame_id == "base"
            assert back.position == (1.0, 2.0)


def test_messages_without_loops_are_written_in_one_piece() -> None:
    # Parts are joined and written once (a node frames such a message without a list scan);
    # a bad field then leaves the buffer untouched.  Loops and uint8[] payloads still stream.
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import Image

    class Writes(list[bytes]):
        def write(self, data: bytes) -> None:
            self.append(bytes(data))

    odometry = Odometry(child_frame_id="base_link")
    odometry.header.frame_id = "odom"
    writes = Writes()
    odometry.serialize(writes)
    assert writes == [serialize(odometry)]
    odometry.pose.pose.position.x = "far"
    writes.clear()
    with pytest.raises(SerializationError, match=r"field pose\.pose\.position\.x must be float type"):
        odometry.serialize(writes)
    assert writes == []
    payload = bytes(1000)
    writes.clear()
    Image(data=payload).serialize(writes)
    assert writes[-1] == payload


def test_uint8_arrays_take_bytes_lists_and_buffers() -> None:
    from std_msgs.msg import UInt8MultiArray

    expected = serialize(UInt8MultiArray(data=b"\x01\x02\x03"))
    for value in ([1, 2, 3], (1, 2, 3), bytearray(b"\x01\x02\x03"), memoryview(b"\x01\x02\x03"),
                  numpy.array([1, 2, 3], dtype=numpy.uint8)):
        assert serialize(UInt8MultiArray(data=value)) == expected
    assert UInt8MultiArray().deserialize(expected).data == b"\x01\x02\x03"


def test_numpy_variants() -> None:
    from sensor_msgs.msg import LaserScan

    ranges = numpy.array([1.0, 2.0, 3.0], dtype=numpy.float32)
    msg = LaserScan(ranges=ranges)
    data = serialize(msg)
    buff = io.BytesIO()
    msg.serialize_numpy(buff, numpy)
    assert buff.getvalue() == data
    back = LaserScan().deserialize_numpy(data, numpy)
    assert isinstance(back.ranges, numpy.ndarray) and back.ranges.dtype == numpy.float32
    assert back.ranges.tolist() == [1.0, 2.0, 3.0]
    assert LaserScan().deserialize(data).ranges == (1.0, 2.0, 3.0)


def test_large_payload_keeps_one_contiguous_copy() -> None:
    from sensor_msgs.msg import Image

    payload = bytes(range(256)) * 4096
    data = serialize(Image(height=1, width=len(payload), encoding="mono8", step=len(payload), data=payload))
    back = Image().deserialize(memoryview(data))
    assert type(back.data) is bytes and back.data == payload


@pytest.mark.parametrize(
    ("make", "problem"),
    [
        (lambda m: setattr(m.linear, "x", "fast"), "field linear.x must be float type"),
        (lambda m: setattr(m, "angular", None), "field angular must be a geometry_msgs/Vector3 message"),
    ],
)
def test_serialization_errors_name_the_field(make: Any, problem: str) -> None:
    from geometry_msgs.msg import Twist

    msg = Twist()
    make(msg)
    with pytest.raises(SerializationError, match=f"cannot serialize geometry_msgs/Twist: {problem}"):
        serialize(msg)


def test_out_of_range_and_wrong_types() -> None:
    from sensor_msgs.msg import Image
    from std_msgs.msg import Header, Int8, String

    with pytest.raises(SerializationError, match=r"field data value 128 is out of range for int8 \[-128, 127\]"):
        serialize(Int8(128))
    with pytest.raises(SerializationError, match="field data must be a string, got int"):
        serialize(String(5))
    with pytest.raises(SerializationError, match="field stamp must be of type Time"):
        serialize(Header(stamp=1.5))
    with pytest.raises(SerializationError, match="field height must be an integer type"):
        serialize(Image(height=1.5))
    with pytest.raises(SerializationError, match=r"field data\[0\]"):
        serialize(Image(data=[300]))


def test_a_fixed_array_of_the_wrong_length_is_refused() -> None:
    from geometry_msgs.msg import PoseWithCovariance

    with pytest.raises(SerializationError, match="field covariance must have exactly 36 elements, got 3"):
        serialize(PoseWithCovariance(covariance=[0.0] * 3))


def test_short_buffers_name_the_field() -> None:
    from geometry_msgs.msg import PoseStamped
    from sensor_msgs.msg import Image

    data = serialize(PoseStamped())
    with pytest.raises(DeserializationError, match=r"field pose\.orientation"):
        PoseStamped().deserialize(data[:-8])
    with pytest.raises(DeserializationError, match=r"field header\.frame_id"):
        PoseStamped().deserialize(data[:12] + struct.pack("<I", 1000))
    image = serialize(Image(data=b"abc"))
    with pytest.raises(DeserializationError, match="field data: needs 4294967295 bytes"):
        Image().deserialize(image[:-7] + struct.pack("<I", 0xFFFFFFFF))


def test_garbage_never_escapes_as_another_exception() -> None:
    from rosgraph_msgs.msg import Log

    data = serialize(filled(Log))
    for cut in range(len(data)):
        with pytest.raises(DeserializationError):
            Log().deserialize(data[:cut])


def test_str_is_the_yaml_like_text() -> None:
    from std_msgs.msg import Header, String

    assert str(String("hi")) == 'data: "hi"'
    assert str(String()) == "data: ''"
    assert str(Header(seq=3, stamp=Time(5, 7), frame_id="map")) == (
        'seq: 3\nstamp: \n  secs: 5\n  nsecs:         7\nframe_id: "map"'
    )


def test_deserializing_garbage_raises_only_deserialization_errors() -> None:
    # Seeded fuzz over every shipped message and service type: random bytes, a valid message with
    # bytes flipped or appended, and lengths replaced by huge values. deserialize must raise
    # DeserializationError (or succeed), never IndexError/MemoryError/struct.error, and never hang.
    import random

    rng = random.Random(7)
    classes = []
    for pkg in ("std_msgs", "geometry_msgs", "sensor_msgs", "nav_msgs", "visualization_msgs", "trajectory_msgs",
                "actionlib_msgs", "diagnostic_msgs", "rosgraph_msgs", "shape_msgs", "stereo_msgs", "tf2_msgs",
                "turtlesim", "std_srvs"):
        for sub in ("msg", "srv"):
            try:
                module = importlib.import_module(f"{pkg}.{sub}")
            except ImportError:
                continue
            found = [getattr(module, name) for name in dir(module)]
            classes += [c for c in found if isinstance(c, type) and hasattr(c, "_md5sum") and hasattr(c, "_slot_types")]
    assert len(classes) > 150
    for cls in classes:
        buff = io.BytesIO()
        cls().serialize(buff)
        valid = buff.getvalue()
        for i in range(40):
            if i < 15:
                data = bytearray(rng.getrandbits(8) for _ in range(rng.randint(0, 48)))
            elif i < 30:
                data = bytearray(valid + bytes(rng.getrandbits(8) for _ in range(rng.randint(0, 12))))
                for _ in range(rng.randint(1, 3)):
                    if data:
                        data[rng.randrange(len(data))] = rng.getrandbits(8)
            else:
                data = bytearray(valid)
                if len(data) >= 4:
                    at = rng.randrange(len(data) - 3)
                    data[at : at + 4] = struct.pack("<I", rng.choice([0xFFFFFFFF, 0x7FFFFFFF, 1 << 28]))
            try:
                cls().deserialize(bytes(data))
            except DeserializationError:
                pass
