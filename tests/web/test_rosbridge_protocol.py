"""kame.rosbridge's pure parts: rosbridge's JSON and CBOR encodings, frames, fragments, png,
pacing, globs, rosapi's TypeDefs and its srv types' md5sums."""

from __future__ import annotations

import base64
import importlib
import io
import json
import math
import struct

import cbor2
import pytest
from PIL import Image as PILImage

from geometry_msgs.msg import Twist
from kame.rosbridge import conversion, globs, protocol
from kame.rosbridge.pacing import Pacing
from kame.rosbridge.typedefs import typedefs
from kame.rostime import Duration, Time
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import CameraInfo, Image, JointState
from std_msgs.msg import Float32MultiArray, Int8MultiArray

# Noetic's generated code for rosapi 0.11 (the message and every service): the md5sums ROS has
ROSAPI_MD5 = {
    "TypeDef": "80597571d79bbeef6c9c4d98f30116a0", "DeleteParam": "c1f3d28f1b044c871e6eff2e9fc3c667",
    "GetActionServers": "46807ba271844ac5ba4730a47556b236", "GetParam": "e36fd90759dbac1c5159140a7fa8c644",
    "GetParamNames": "dc7ae3609524b18034e49294a4ce670e", "GetTime": "556a4fb76023a469987922359d08a844",
    "HasParam": "ed3df286bd6dff9b961770f577454ea9", "MessageDetails": "f9c88144f6f6bd888dd99d4e0411905d",
    "NodeDetails": "e1d0ced5ab8d5edb5fc09c98eb1d46f6", "Nodes": "3d07bfda1268b4f76b16b7ba8a82665d",
    "Publishers": "cb37f09944e7ba1fc08ee38f7a94291d", "SearchParam": "dfadc39f113c1cc6d7759508d8461d5a",
    "ServiceHost": "a1b60006f8ee69637c856c94dd192f5a", "ServiceNode": "bd2a0a45fd7a73a86c8d6051d5a6db8a",
    "ServiceProviders": "f30b41d5e347454ae5483ee95eef5cc6",
    "ServiceRequestDetails": "f9c88144f6f6bd888dd99d4e0411905d",
    "ServiceResponseDetails": "f9c88144f6f6bd888dd99d4e0411905d", "ServiceType": "0e24a2dcdf70e483afc092a35a1f15f7",
    "Services": "e44a7e7bcb900acadbcc28b132378f0c", "ServicesForType": "93e9fe8ae5a9136008e260fe510bd2b0",
    "SetParam": "bc6ccc4a57f61779c8eaae61e9f422e0", "Subscribers": "cb387b68f5b29bc1456398ee8476b973",
    "TopicType": "0d30b3f53a0fd5036523a7141e524ddf", "Topics": "d966d98fc333fa1f3135af765eac1ba8",
    "TopicsAndRawTypes": "e1432466c8f64316723276ba07c59d12", "TopicsForType": "56f77ff6da756dd27c1ed16ec721072a",
}


@pytest.mark.parametrize("name", sorted(ROSAPI_MD5))
def test_rosapi_types_have_noetics_md5sums(name: str) -> None:
    module = importlib.import_module("rosapi.msg" if name == "TypeDef" else "rosapi.srv")
    assert getattr(module, name)._md5sum == ROSAPI_MD5[name]


def test_json_encoding_is_rosbridges() -> None:
    img = Image(height=1, width=2, encoding="rgb8", step=6, data=bytes(range(6)))
    img.header.stamp = Time(5, 7)
    img.header.frame_id = "cam"
    value = conversion.to_json(img)
    assert value["data"] == base64.b64encode(bytes(range(6))).decode()
    assert value["header"] == {"seq": 0, "stamp": {"secs": 5, "nsecs": 7}, "frame_id": "cam"}
    info = conversion.to_json(CameraInfo(D=[1.0, math.nan]))
    assert info["D"] == [1.0, None]
    assert len(info["K"]) == 9
    text = protocol.encode_json({"op": "publish", "msg": info})  # strict JSON: no NaN literal
    assert "NaN" not in text


def test_json_round_trip() -> None:
    joint = JointState(name=["a", "b"], position=[1.5, -2.0], velocity=[], effort=[0.25, 0.5])
    joint.header.stamp = Time(1, 2)
    back = conversion.from_json(JointState, json.loads(json.dumps(conversion.to_json(joint))))
    assert back == joint
    img = Image(height=1, width=1, encoding="mono8", step=1, data=b"\x07")
    assert conversion.from_json(Image, conversion.to_json(img)) == img
    # a uint8[] given as a list of numbers, as some clients send it
    assert conversion.from_json(Image, {"data": [1, 2, 255]}).data == b"\x01\x02\xff"


def test_missing_fields_keep_defaults_and_now_is_the_callers_time() -> None:
    twist = conversion.from_json(Twist, {"linear": {"x": 2}})
    assert (twist.linear.x, twist.linear.y, twist.angular.z) == (2.0, 0.0, 0.0)
    log = conversion.from_json(Log, {"header": {"stamp": "now"}}, now=lambda: Time(42, 1))
    assert log.header.stamp == Time(42, 1)


@pytest.mark.parametrize("cls,value,words", [
    (Twist, {"linear": {"x": "fast"}}, "linear.x: expected a number"),
    (Twist, {"linear": {"w": 1.0}}, "does not have a field w"),
    (Twist, {"linear": 3}, "expected an object"),
    (Log, {"level": 300}, "out of range for byte"),
    (Log, {"level": True}, "expected an integer"),
    (Log, {"topics": "a"}, "expected a list"),
    (Log, {"header": {"stamp": {"secs": "x"}}}, "stamp.secs: expected an integer"),
    (CameraInfo, {"K": [1.0]}, "needs 9 elements"),
    (Image, {"data": "%%%"}, "base64"),
    (Image, [], "expected an object"),
])
def test_values_that_do_not_fit_say_which_field(cls: type, value: object, words: str) -> None:
    with pytest.raises(conversion.ConversionError, match=words):
        conversion.from_json(cls, value)


def test_cbor_uses_typed_arrays_and_bytes() -> None:
    msg = Float32MultiArray(data=[1.0, 2.5])
    value = cbor2.loads(protocol.encode_cbor(conversion.to_cbor_value(msg, protocol.cbor_tag)))
    assert value["data"].tag == 85
    assert struct.unpack("<2f", value["data"].value) == (1.0, 2.5)
    ints = cbor2.loads(protocol.encode_cbor(conversion.to_cbor_value(Int8MultiArray(data=[-1, 2]), protocol.cbor_tag)))
    assert ints["data"].tag == 72
    img = Image(data=b"\x00\x01")
    img.header.stamp = Time(3, 4)
    decoded = cbor2.loads(protocol.encode_cbor(conversion.to_cbor_value(img, protocol.cbor_tag)))
    assert decoded["data"] == b"\x00\x01"
    assert decoded["header"]["stamp"] == {"secs": 3, "nsecs": 4}


@pytest.mark.parametrize("frame,words", [
    ("{not json", "malformed JSON"),
    (b"\xa1", "malformed CBOR"),  # a map cut short
    (b"\x5b\x00\x00\x00\x10\x00\x00\x00\x00", "malformed CBOR"),  # announces 64 GiB of bytes, sends none
    ("[" * 100_000, "malformed JSON"),  # nested past the parser's recursion
    ("[1, 2]", "not an object"),
    ('{"topic": "/a"}', "no 'op'"),
])
def test_frames_that_are_not_ops(frame: str | bytes, words: str) -> None:
    with pytest.raises(protocol.ProtocolError, match=words):
        protocol.decode_frame(frame)


def test_cbor_frames_are_ops_too() -> None:
    assert protocol.decode_frame(cbor2.dumps({"op": "publish", "topic": "/a"}))["topic"] == "/a"


def test_fields_check_kinds() -> None:
    fields = protocol.Fields({"op": "subscribe", "id": "s1", "topic": 5, "throttle_rate": -1, "compression": "zip"})
    for check in (lambda: fields.string("topic"), lambda: fields.number("throttle_rate", 0),
                  lambda: fields.compression()):
        with pytest.raises(protocol.ProtocolError) as caught:
            check()
        assert caught.value.op_id == "s1"


def test_fragments_and_their_reassembly() -> None:
    text = protocol.encode_json({"op": "publish", "topic": "/t", "msg": {"data": "x" * 100}})
    parts = protocol.fragments(text, 30, "m1")
    assert len(parts) > 1
    ops = [json.loads(p) for p in parts]
    assert [o["num"] for o in ops] == list(range(len(ops)))
    assert {o["total"] for o in ops} == {len(ops)}
    joined = protocol.Defragmenter(1000)
    results = [joined.add(o) for o in reversed(ops)]
    assert results[:-1] == [None] * (len(ops) - 1)
    assert results[-1] == text
    assert protocol.fragments(text, 0, "m") == [text]
    many = protocol.fragments("z" * 5000, 1, "m2")
    assert len(many) == protocol.MAX_FRAGMENTS
    assert "".join(json.loads(f)["data"] for f in many) == "z" * 5000


def test_defragmenter_is_bounded() -> None:
    joined = protocol.Defragmenter(max_bytes=10, max_messages=2)
    with pytest.raises(protocol.ProtocolError, match="larger than 10"):
        joined.add({"op": "fragment", "id": "a", "data": "x" * 11, "num": 0, "total": 2})
    joined.add({"op": "fragment", "id": "b", "data": "b", "num": 0, "total": 2})
    joined.add({"op": "fragment", "id": "c", "data": "c", "num": 0, "total": 2})
    joined.add({"op": "fragment", "id": "d", "data": "d", "num": 0, "total": 2})  # "b", the oldest, is given up
    assert joined.add({"op": "fragment", "id": "c", "data": "C", "num": 1, "total": 2}) == "cC"
    assert joined.add({"op": "fragment", "id": "b", "data": "B", "num": 1, "total": 2}) is None  # begun anew
    with pytest.raises(protocol.ProtocolError, match="num"):
        joined.add({"op": "fragment", "id": "d", "data": "x", "num": 5, "total": 2})


def test_png_compression_is_rosbridges() -> None:
    text = protocol.encode_json({"op": "publish", "topic": "/t", "msg": {"data": "hello"}})
    op = json.loads(protocol.png_compress(text))
    assert op["op"] == "png"
    pixels = PILImage.open(io.BytesIO(base64.b64decode(op["data"]))).convert("RGB").tobytes()
    assert json.loads(pixels.decode()) == json.loads(text)  # padded with newlines, which JSON skips


def test_status_levels() -> None:
    assert protocol.wants_status("error", "error")
    assert not protocol.wants_status("error", "warning")
    assert protocol.wants_status("info", "warning")
    assert not protocol.wants_status("none", "error")
    assert protocol.status("error", "bad", "x1") == {"op": "status", "level": "error", "msg": "bad", "id": "x1"}


def test_pacing_without_throttle_sends_everything() -> None:
    pacing: Pacing[int] = Pacing()
    assert [pacing.offer(i, 0.0) for i in range(3)] == [[0], [1], [2]]


def test_throttle_without_queue_drops_in_between() -> None:
    pacing: Pacing[int] = Pacing(throttle_rate_ms=100)
    assert pacing.offer(1, 0.0) == [1]
    assert pacing.offer(2, 0.05) == []
    assert pacing.offer(3, 0.1) == [3]
    assert pacing.dropped == 1
    assert pacing.next_due() is None


def test_throttle_with_queue_keeps_the_newest_and_sends_them_in_turn() -> None:
    pacing: Pacing[int] = Pacing(throttle_rate_ms=100, queue_length=2)
    assert pacing.offer(1, 0.0) == [1]
    for item, now in ((2, 0.01), (3, 0.02), (4, 0.03)):
        assert pacing.offer(item, now) == []
    assert pacing.dropped == 1  # 2 made room for 4
    assert pacing.next_due() == pytest.approx(0.1)
    assert pacing.due(0.05) == []
    assert pacing.due(0.1) == [3]
    assert pacing.due(0.15) == []
    assert pacing.due(0.2) == [4]
    assert pacing.next_due() is None


def test_globs() -> None:
    assert globs.parse("[*]") is None
    assert globs.parse("") is None
    patterns = globs.parse("[/turtle1/*, '/rosout']")
    assert patterns == ("/turtle1/*", "/rosout")
    assert globs.allows(patterns, "/turtle1/pose")
    assert not globs.allows(patterns, "/secret")


def test_typedefs_as_rosapi_gives_them() -> None:
    defs = {t.type: t for t in typedefs(Log)}
    log = defs["rosgraph_msgs/Log"]
    assert log.fieldtypes[0] == "std_msgs/Header"
    assert log.fieldarraylen[log.fieldnames.index("topics")] == 0
    assert dict(zip(log.constnames, log.constvalues, strict=True))["ERROR"] == "8"
    assert defs["std_msgs/Header"].fieldtypes == ("uint32", "time", "string")
    assert defs["time"].fieldnames == ("secs", "nsecs")
    assert typedefs(CameraInfo)[0].fieldarraylen[typedefs(CameraInfo)[0].fieldnames.index("K")] == 9


def test_durations_round_trip() -> None:
    from std_msgs.msg import Duration as DurationMsg

    value = conversion.to_json(DurationMsg(Duration(-3, 5)))
    assert value == {"data": {"secs": -3, "nsecs": 5}}
    assert conversion.from_json(DurationMsg, value).data == Duration(-3, 5)
