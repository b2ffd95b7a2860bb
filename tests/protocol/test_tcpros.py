"""kame.protocol.tcpros against the real ROS 1 bytes of tests/data/ros1_vectors.json (§6)."""

from __future__ import annotations

import os
import random
import struct
from typing import Any

import pytest

from kame.protocol import tcpros as t
from tests.ros1_vectors import vectors

HEADERS: list[dict[str, Any]] = vectors()["tcpros_headers"]
FRAMES: list[dict[str, Any]] = vectors()["tcpros_frames"]
MD5 = "992ce8a1687cec8c8bd883ec73ca41d1"
SRV_MD5 = "09fb03525b03e7ea1fd3992bafd87e16"


def _vec(description_start: str, table: list[dict[str, Any]] = HEADERS) -> dict[str, Any]:
    (found,) = [v for v in table if v["description"].startswith(description_start)]
    return found


def _frame_bytes(description_start: str) -> bytes:
    return bytes.fromhex(_vec(description_start, FRAMES)["hex"])


# ------------------------------------------------------------------------------ header codec


@pytest.mark.parametrize("vec", HEADERS, ids=[v["description"] for v in HEADERS])
def test_header_vectors_encode_byte_exact(vec: dict[str, Any]) -> None:
    wire = bytes.fromhex(vec["hex"])
    assert t.encode_header(vec["fields"]) == wire
    assert t.encode_header_fields(vec["fields"]) == wire[4:]
    # the order we are given does not matter: we sort as rospy and roscpp do
    assert t.encode_header(dict(reversed(list(vec["fields"].items())))) == wire


@pytest.mark.parametrize("vec", HEADERS, ids=[v["description"] for v in HEADERS])
def test_header_vectors_decode(vec: dict[str, Any]) -> None:
    wire = bytes.fromhex(vec["hex"])
    assert t.decode_header(wire) == vec["fields"]
    assert t.decode_header_fields(wire[4:]) == vec["fields"]
    assert t.decode_header_fields(memoryview(wire)[4:]) == vec["fields"]
    assert t.decode_header_fields_raw(bytearray(wire[4:])) == {k: v.encode() for k, v in vec["fields"].items()}


@pytest.mark.parametrize("vec", HEADERS, ids=[v["description"] for v in HEADERS])
def test_header_vectors_incremental(vec: dict[str, Any]) -> None:
    wire = bytes.fromhex(vec["hex"])
    reader = t.HeaderReader()
    for i in range(len(wire) - 1):
        assert reader.feed(wire[i : i + 1]) is None
    assert reader.feed(wire[-1:]) == vec["fields"]
    assert reader.done and reader.trailing == b""


def test_header_sorting_is_by_key_not_by_line() -> None:
    # "a-b=" sorts before "a=" bytewise, but the key "a" sorts before "a-b"
    body = t.encode_header_fields({"a-b": "2", "a": "1"})
    assert body == b"\x03\x00\x00\x00a=1\x05\x00\x00\x00a-b=2"


def test_header_values_split_at_first_equals_any_order_binary() -> None:
    fields = {"message_definition": "int32 X=1\nstring s # a=b\n", "z": "", "a": "x=y=z"}
    lines = [b"z=", b"a=x=y=z", b"message_definition=int32 X=1\nstring s # a=b\n"]
    body = b"".join(struct.pack("<I", len(f)) + f for f in lines)
    assert t.decode_header_fields(body) == fields
    assert t.decode_header_fields(t.encode_header_fields(fields)) == fields
    raw = t.encode_header_fields({"op": b"\x02", "conn": struct.pack("<I", 7), "topic": "/t"})
    assert t.decode_header_fields_raw(raw) == {"op": b"\x02", "conn": b"\x07\x00\x00\x00", "topic": b"/t"}
    with pytest.raises(t.TcprosError, match="value of 'op' is not UTF-8") as info:
        t.decode_header_fields(t.encode_header_fields({"op": b"\xff"}))
    assert info.value.remote


def test_header_duplicate_key_last_wins_and_empty_header() -> None:
    body = b"\x03\x00\x00\x00k=1\x03\x00\x00\x00k=2"
    assert t.decode_header_fields(body) == {"k": "2"}
    assert t.decode_header(b"\x00\x00\x00\x00") == {}
    assert t.encode_header({}) == b"\x00\x00\x00\x00"


@pytest.mark.parametrize(
    ("body", "message"),
    [
        (b"\x00\x00\x00\x00", "zero-length field at offset 0"),
        (b"\x03\x00\x00\x00k=1\x00\x00\x00\x00", "zero-length field at offset 7"),
        (b"\x05\x00\x00\x00topic", "field without '='"),
        (b"\x10\x00\x00\x00k=1", "claims 16 bytes but only 3 remain"),
        (b"\x03\x00\x00\x00k=1\x02\x00", "2 stray byte"),
        (b"\xff\xff\xff\xffgarbage", "claims 4294967295 bytes"),
        (b"\x03\x00\x00\x00\xff=1", "key b'\\xff' is not UTF-8"),
    ],
)
def test_malformed_header_bodies(body: bytes, message: str) -> None:
    with pytest.raises(t.TcprosError, match="malformed connection header") as info:
        t.decode_header_fields(body)
    assert message in str(info.value)
    assert info.value.remote


def test_decode_header_checks_outer_length() -> None:
    with pytest.raises(t.TcprosError, match="truncated"):
        t.decode_header(b"\x01\x00")
    with pytest.raises(t.TcprosError, match="says 9 bytes but 3 follow"):
        t.decode_header(b"\x09\x00\x00\x00k=1")


def test_encode_header_refuses_key_with_equals() -> None:
    with pytest.raises(t.TcprosError, match="contains '='") as info:
        t.encode_header({"a=b": "c"})
    assert not info.value.remote


# ------------------------------------------------------------------------------ header reader


def test_header_reader_keeps_what_follows_the_header() -> None:
    # a latched publisher sends its last message right after its reply header
    header = bytes.fromhex(_vec("publisher -> subscriber reply")["hex"])
    frame = _frame_bytes("topic message frame")
    reader = t.HeaderReader()
    assert reader.feed(header[:10]) is None
    fields = reader.feed(header[10:] + frame)
    assert fields == _vec("publisher -> subscriber reply")["fields"]
    assert reader.trailing == frame
    assert [bytes(f) for f in t.FrameReader().feed(reader.trailing)] == [b"\x05\x00\x00\x00hello"]
    with pytest.raises(t.TcprosError, match="after the header was complete"):
        reader.feed(b"x")


def test_header_reader_refuses_oversize_length_at_once() -> None:
    reader = t.HeaderReader(max_header=1000)
    with pytest.raises(t.TcprosError, match="1001 bytes refused"):
        reader.feed(struct.pack("<I", 1001))
    # an HTTP request is not TCPROS: refused on its first four bytes with the default limit
    with pytest.raises(t.TcprosError, match="refused"):
        t.HeaderReader().feed(b"GET / HTTP/1.1\r\n")


def test_header_reader_malformed_body() -> None:
    with pytest.raises(t.TcprosError, match="zero-length field"):
        t.HeaderReader().feed(b"\x04\x00\x00\x00\x00\x00\x00\x00")


# ------------------------------------------------------------------------------ frames


def test_frame_vectors_encode_and_decode() -> None:
    hello = _frame_bytes("topic message frame")
    assert t.encode_frame(b"\x05\x00\x00\x00hello") == hello
    assert t.encode_frame(memoryview(b"\x05\x00\x00\x00hello")) == hello
    assert t.encode_frame_prefix(9) + b"\x05\x00\x00\x00hello" == hello
    request = _frame_bytes("service request frame")
    assert t.encode_frame(b"\x01") == request
    frames = t.FrameReader().feed(hello + request)
    assert [bytes(f) for f in frames] == [b"\x05\x00\x00\x00hello", b"\x01"]
    assert all(f.readonly for f in frames)


def test_frame_parts_send_the_payload_itself() -> None:
    payload = memoryview(b"..\x05\x00\x00\x00hello..")[2:-2]
    prefix, body = t.frame_parts(payload)
    assert body is payload  # no copy: the caller's buffer goes to sendmsg as it is
    assert prefix + bytes(body) == _frame_bytes("topic message frame")


def _stream(count: int, seed: int) -> tuple[bytes, list[bytes]]:
    rng = random.Random(seed)
    payloads = [bytes(rng.getrandbits(8) for _ in range(rng.choice([0, 1, 3, 4, 5, 17, 300, 5000])))
                for _ in range(count)]
    payloads[:2] = [b"\x05\x00\x00\x00hello", b"\x01"]  # the vectors' payloads
    return b"".join(t.encode_frame(p) for p in payloads), payloads


def test_many_frames_in_one_feed() -> None:
    wire, payloads = _stream(500, seed=1)
    reader = t.FrameReader()
    frames = reader.feed(wire)
    assert [bytes(f) for f in frames] == payloads
    assert reader.pending == 0
    # zero-copy: every frame is a view of the one bytes object we fed
    assert all(f.obj is wire for f in frames)


def test_frames_byte_by_byte() -> None:
    wire, payloads = _stream(60, seed=2)
    reader = t.FrameReader()
    got: list[bytes] = []
    for i in range(len(wire)):
        got += [bytes(f) for f in reader.feed(wire[i : i + 1])]
    assert got == payloads
    assert reader.pending == 0


@pytest.mark.parametrize("seed", range(5))
def test_frames_in_random_chunks(seed: int) -> None:
    wire, payloads = _stream(300, seed=seed)
    rng = random.Random(1000 + seed)
    reader = t.FrameReader()
    got: list[bytes] = []
    pos = 0
    while pos < len(wire):
        size = rng.choice([1, 2, 3, 5, 7, 64, 1000, 7000])
        chunk = wire[pos : pos + size]
        # callers may pass bytearray/memoryview (copied once, since they may reuse the buffer)
        got += [bytes(f) for f in reader.feed(rng.choice([bytes, bytearray, memoryview])(chunk))]
        pos += size
    assert got == payloads


@pytest.mark.parametrize("seed", range(3))
def test_frames_through_get_buffer(seed: int) -> None:
    payloads = [b"a" * 10, b"b" * 200_000, b"", b"c" * 3, b"d" * 100_000, b"e"]
    wire = b"".join(t.encode_frame(p) for p in payloads)
    rng = random.Random(seed)
    reader = t.FrameReader()
    got: list[bytes] = []
    pos = 0
    direct = 0
    while pos < len(wire):
        buf = reader.get_buffer(65536)
        n = min(len(buf), rng.choice([1, 9, 4096, 65536]), len(wire) - pos)
        buf[:n] = wire[pos : pos + n]  # what sock.recv_into(buf) would do
        if buf.obj is reader._body:
            direct += 1  # the large frame's own storage: no copy after the kernel's
        del buf
        got += [bytes(f) for f in reader.buffer_updated(n)]
        pos += n
    assert got == payloads
    assert direct > 0
    assert reader.pending == 0


def test_oversize_frame_refused_without_allocation() -> None:
    reader = t.FrameReader()
    with pytest.raises(t.TcprosError, match="4294967295 bytes refused") as info:
        reader.feed(b"\xff\xff\xff\xff")  # 4 GiB
    assert info.value.remote
    small = t.FrameReader(max_frame=100)
    assert [bytes(f) for f in small.feed(t.encode_frame(b"x" * 100))] == [b"x" * 100]
    with pytest.raises(t.TcprosError, match="101 bytes refused"):
        small.feed(b"\x65\x00")  # split prefix: refused once complete
        small.feed(b"\x00\x00")
    # a huge but allowed prefix commits what arrived, not its size: 8 readers told 64 MiB each
    # hold a few pages, not 512 MiB (64 MiB each at once, repeated, drove a subscriber to 1.6 GB)
    before = _resident_bytes()
    readers = [t.FrameReader() for _ in range(8)]
    for reader in readers:
        assert reader.feed(struct.pack("<I", 64 << 20) + b"abc") == [] and reader.pending == 7
    assert _resident_bytes() - before < 16 << 20
    for reader in readers:
        reader.release()
        assert reader.pending == 0 and reader.frame_size == 0


def _resident_bytes() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_empty_frames_and_pending() -> None:
    reader = t.FrameReader()
    assert [bytes(f) for f in reader.feed(b"\x00\x00\x00\x00" * 3)] == [b"", b"", b""]
    assert reader.feed(b"\x02\x00") == [] and reader.pending == 2
    assert reader.feed(b"\x00\x00x") == [] and reader.pending == 5
    assert [bytes(f) for f in reader.feed(b"y\x00\x00\x00\x00")] == [b"xy", b""]
    assert reader.pending == 0


# ------------------------------------------------------------------------------ service responses


def test_service_response_vectors() -> None:
    success = _frame_bytes("service success response")
    assert success == bytes.fromhex("01" "07000000" "01" "02000000" "6f6b")  # the spec's example
    rospy_failure = _frame_bytes("service failure response from rospy")
    roscpp_failure = _frame_bytes("service failure response from roscpp")
    assert t.encode_service_response(True, b"\x01\x02\x00\x00\x00ok") == success
    assert t.encode_service_response(False, "service cannot process request: nope") == rospy_failure
    assert t.encode_service_response(False, "") == roscpp_failure

    reader = t.ServiceResponseReader()
    got = reader.feed(success + rospy_failure + roscpp_failure)
    assert got == [
        t.ServiceResponse(True, b"\x01\x02\x00\x00\x00ok"),
        t.ServiceResponse(False, b"service cannot process request: nope"),
        t.ServiceResponse(False, b""),
    ]
    assert got[1].error_text == "service cannot process request: nope"
    assert got[2].error_text == ""
    assert reader.pending == 0


def test_service_responses_byte_by_byte() -> None:
    wire = b"".join(_frame_bytes(d) for d in ("service success", "service failure response from rospy",
                                               "service failure response from roscpp")) * 3
    reader = t.ServiceResponseReader()
    got = []
    for i in range(len(wire)):
        got += reader.feed(wire[i : i + 1])
    assert [r.ok for r in got] == [True, False, False] * 3


def test_service_responses_parsed_in_place_keep_what_follows() -> None:
    one = t.encode_service_response(True, b"abc")
    wire = one * 3 + one[:6]
    reader = t.ServiceResponseReader()
    assert reader.feed(wire) == [t.ServiceResponse(True, b"abc")] * 3 and reader.pending == 6
    assert reader.feed(one[6:]) == [t.ServiceResponse(True, b"abc")] and reader.pending == 0


def test_service_response_reader_says_how_much_is_missing() -> None:
    reader = t.ServiceResponseReader()
    assert reader.feed(b"\x01\x0a\x00") == [] and reader.missing == 0  # prefix incomplete: unknown
    assert reader.feed(b"\x00\x00abc") == [] and reader.missing == 7
    assert reader.feed(b"defghij") == [t.ServiceResponse(True, b"abcdefghij")] and reader.missing == 0


def test_service_response_errors() -> None:
    with pytest.raises(t.TcprosError, match="ok byte is 7"):
        t.ServiceResponseReader().feed(b"\x07\x00\x00\x00\x00")
    with pytest.raises(t.TcprosError, match="refused"):
        t.ServiceResponseReader().feed(b"\x01\xff\xff\xff\xff")


# ------------------------------------------------------------------------------ handshakes

CHATTER = t.TopicSpec(type="std_msgs/String", md5sum=MD5, message_definition="string data\n", latching=True)
PUBS = {"/chatter": CHATTER}
SET_BOOL = t.ServiceSpec(type="std_srvs/SetBool", md5sum=SRV_MD5)
SRVS = {"/set_bool": SET_BOOL}


def test_builders_reproduce_the_vectors() -> None:
    assert t.subscriber_header_fields(callerid="/listener", topic="/chatter", type="std_msgs/String", md5sum=MD5,
                                      message_definition="string data\n") == _vec("rospy subscriber")["fields"]
    assert t.subscriber_header_fields(callerid="/listener", topic="/chatter", type="std_msgs/String", md5sum=MD5,
                                      message_definition=None) == _vec("roscpp subscriber")["fields"]
    assert t.subscriber_header_fields(callerid="/rostopic_1_2", topic="/chatter", type="*",
                                      md5sum="*") == _vec("wildcard subscriber")["fields"]
    reply = t.publisher_reply_fields(callerid="/talker", topic="/chatter", spec=CHATTER)
    assert t.encode_header(reply) == bytes.fromhex(_vec("publisher -> subscriber reply")["hex"])
    assert t.service_client_header_fields(callerid="/client", service="/set_bool",
                                          md5sum=SRV_MD5) == _vec("rospy service client")["fields"]
    assert t.service_client_header_fields(callerid="/client", service="/set_bool", md5sum=SRV_MD5,
                                          persistent=True)["persistent"] == "1"
    probe = t.service_probe_header_fields(callerid="/rosservice", service="/set_bool")
    assert probe == _vec("rosservice probe")["fields"]
    # the server reply is the union of rospy's and roscpp's: each one's fields, same values
    server = t.service_reply_fields(callerid="/server", service="/set_bool", spec=SET_BOOL)
    for flavour in ("rospy service server reply", "roscpp service server reply"):
        for key, value in _vec(flavour)["fields"].items():
            assert key == "callerid" or server[key] == value
    assert t.Rejected("x").reply == {"error": "x"}
    error = _vec("error reply")
    assert t.encode_header(t.error_header_fields(error["fields"]["error"])) == bytes.fromhex(error["hex"])


def test_classify_connection() -> None:
    assert t.classify_connection(_vec("rospy subscriber")["fields"]) == "topic"
    assert t.classify_connection(_vec("rosservice probe")["fields"]) == "service"
    assert t.classify_connection({"callerid": "/x"}) == t.Rejected("no topic or service name detected")


@pytest.mark.parametrize("vec", ["rospy subscriber", "roscpp subscriber", "wildcard subscriber"])
def test_publisher_accepts_real_subscribers(vec: str) -> None:
    result = t.accept_subscriber(_vec(vec)["fields"], callerid="/talker", publications=PUBS)
    assert isinstance(result, t.SubscriberAccepted)
    assert (result.topic, result.tcp_nodelay) == ("/chatter", False)
    assert result.callerid in ("/listener", "/rostopic_1_2")
    assert t.encode_header(result.reply) == bytes.fromhex(_vec("publisher -> subscriber reply")["hex"])


def test_publisher_tcp_nodelay_and_extra_fields() -> None:
    header = {**_vec("rospy subscriber")["fields"], "tcp_nodelay": "1"}
    result = t.accept_subscriber(header, callerid="/talker", publications=PUBS, extra={"x": "y"})
    assert isinstance(result, t.SubscriberAccepted)
    assert result.tcp_nodelay and result.reply["x"] == "y"


@pytest.mark.parametrize("missing", ["topic", "md5sum", "callerid"])
def test_publisher_requires_fields(missing: str) -> None:
    header = dict(_vec("rospy subscriber")["fields"])
    del header[missing]
    assert t.accept_subscriber(header, callerid="/talker", publications=PUBS) == t.Rejected(
        f"Missing required '{missing}' field")


def test_publisher_unknown_topic() -> None:
    header = {**_vec("rospy subscriber")["fields"], "topic": "/t"}
    assert t.accept_subscriber(header, callerid="/talker", publications=PUBS) == t.Rejected(
        "[/talker] is not a publisher of [/t]. Topics are [['/chatter', 'std_msgs/String']]")


def test_publisher_md5_mismatch_texts() -> None:
    base = _vec("rospy subscriber")["fields"]
    wrong_type = {**base, "type": "std_msgs/Foo", "md5sum": "0" * 32}
    rejected = t.accept_subscriber(wrong_type, callerid="/talker", publications=PUBS)
    assert rejected == t.Rejected(_vec("error reply")["fields"]["error"])  # the real rospy text
    assert rejected == t.Rejected("topic types do not match: [std_msgs/Foo] vs. [std_msgs/String]")
    same_type = {**base, "md5sum": "0" * 32}
    assert t.accept_subscriber(same_type, callerid="/talker", publications=PUBS) == t.Rejected(
        f"Client [/listener] wants topic [/chatter] to have datatype/md5sum [std_msgs/String/{'0' * 32}], "
        f"but our version has [std_msgs/String/{MD5}] Dropping connection.")
    no_type = {k: v for k, v in same_type.items() if k != "type"}
    assert t.accept_subscriber(no_type, callerid="/talker", publications=PUBS) == t.Rejected(
        f"Client [/listener] wants topic [/chatter] to have datatype/md5sum [std_msgs/String/{'0' * 32}], "
        f"but our version has [std_msgs/String/{MD5}] Dropping connection.")


def test_publisher_type_not_checked_when_md5_matches_or_wildcard() -> None:
    base = _vec("rospy subscriber")["fields"]
    assert isinstance(t.accept_subscriber({**base, "type": "other/Type"}, callerid="/talker", publications=PUBS),
                      t.SubscriberAccepted)
    assert isinstance(t.accept_subscriber({**base, "type": "other/Type", "md5sum": "*"}, callerid="/talker",
                                          publications=PUBS), t.SubscriberAccepted)
    # roscpp also accepts when its own md5sum is '*' (a ShapeShifter publisher)
    relay = {"/chatter": t.TopicSpec(type="*", md5sum="*")}
    assert isinstance(t.accept_subscriber(base, callerid="/relay", publications=relay), t.SubscriberAccepted)


def test_subscriber_checks_publisher_reply() -> None:
    reply = _vec("publisher -> subscriber reply")["fields"]
    info = t.check_publisher_reply(reply)
    assert info == t.ReplyInfo(type="std_msgs/String", md5sum=MD5, callerid="/talker", latching=True,
                               message_definition="string data\n", fields=reply)
    assert t.check_publisher_reply(_vec("error reply")["fields"]) == t.Rejected(
        "remote error reported: topic types do not match: [std_msgs/Foo] vs. [std_msgs/String]")
    for missing in ("md5sum", "type"):
        partial = {k: v for k, v in reply.items() if k != missing}
        assert t.check_publisher_reply(partial) == t.Rejected(f"header missing required field [{missing}]")
    not_latched = t.check_publisher_reply({"md5sum": MD5, "type": "std_msgs/String"})
    assert isinstance(not_latched, t.ReplyInfo) and not not_latched.latching


@pytest.mark.parametrize("vec", ["rospy service server reply", "roscpp service server reply"])
def test_client_checks_service_reply(vec: str) -> None:
    info = t.check_service_reply(_vec(vec)["fields"])
    assert isinstance(info, t.ReplyInfo)
    assert (info.type, info.md5sum) == ("std_srvs/SetBool", SRV_MD5)


@pytest.mark.parametrize(
    ("vec", "persistent", "probe"),
    [("rospy service client", False, False), ("roscpp service client", False, False),
     ("rosservice probe", False, True)],
)
def test_server_accepts_real_clients(vec: str, persistent: bool, probe: bool) -> None:
    result = t.accept_service_client(_vec(vec)["fields"], callerid="/server", services=SRVS)
    assert isinstance(result, t.ServiceClientAccepted)
    assert (result.service, result.persistent, result.probe) == ("/set_bool", persistent, probe)
    assert result.reply["type"] == "std_srvs/SetBool" and result.reply["md5sum"] == SRV_MD5


@pytest.mark.parametrize(("value", "persistent"), [("1", True), ("true", True), ("TRUE", True), ("True", True),
                                                   ("0", False), ("false", False), ("yes", False)])
def test_server_persistent_parsing(value: str, persistent: bool) -> None:
    header = {**_vec("roscpp service client")["fields"], "persistent": value}
    result = t.accept_service_client(header, callerid="/server", services=SRVS)
    assert isinstance(result, t.ServiceClientAccepted) and result.persistent is persistent


@pytest.mark.parametrize("missing", ["service", "md5sum", "callerid"])
def test_server_requires_fields(missing: str) -> None:
    header = dict(_vec("rospy service client")["fields"])
    del header[missing]
    assert t.accept_service_client(header, callerid="/server", services=SRVS) == t.Rejected(
        f"Missing required '{missing}' field")


def test_server_rejections() -> None:
    header = dict(_vec("rospy service client")["fields"])
    assert t.accept_service_client({**header, "md5sum": "a" * 32}, callerid="/server", services=SRVS) == t.Rejected(
        f"request from [/client]: md5sums do not match: [{'a' * 32}] vs. [{SRV_MD5}]")
    assert t.accept_service_client({**header, "service": "/nope"}, callerid="/server", services=SRVS) == t.Rejected(
        "[/server] is not a provider of  [/nope]")


@pytest.mark.parametrize("seed", range(3))
def test_readers_raise_only_tcpros_errors_on_garbage(seed: int) -> None:
    # Seeded fuzz: random bytes (biased to hostile length prefixes and header fields) fed in
    # random chunks. The readers raise TcprosError or wait for more; they never raise anything
    # else, never buffer more than they were given plus a frame's declared (bounded) size.
    rng = random.Random(seed)
    pieces = [struct.pack("<I", 0xFFFFFFFF), struct.pack("<I", 1 << 20), struct.pack("<I", 0),
              struct.pack("<I", 4), b"topic=", b"=", b"\xff\xfe", b"md5sum=*", b"\x00"]
    for _ in range(1500):
        data = b"".join(rng.choice(pieces) if rng.random() < 0.5 else bytes([rng.randrange(256)])
                        for _ in range(rng.randint(0, 24)))
        for reader in (t.HeaderReader(), t.FrameReader(max_frame=1 << 16), t.ServiceResponseReader(max_frame=1 << 16)):
            pos = 0
            try:
                while pos < len(data) and not (isinstance(reader, t.HeaderReader) and reader.done):
                    step = rng.randint(1, 8)
                    reader.feed(data[pos : pos + step])
                    pos += step
            except t.TcprosError:
                pass
        try:
            t.decode_header(data)
        except t.TcprosError:
            pass
