"""Properties of the wire codecs: TCPROS headers and frames survive any split of the stream
and refuse garbage with TcprosError; XML-RPC values round-trip and garbage is MalformedError."""

from __future__ import annotations

import struct

from hypothesis import given
from hypothesis import strategies as st

from kame.protocol import tcpros, xmlrpc
from kame.protocol.header import TcprosError, decode_header, encode_header

from .strategies import XML_TEXT, XMLRPC_VALUES

_KEYS = st.text(st.characters(exclude_characters="=", exclude_categories=("Cs",)), min_size=1, max_size=8)
_HEADERS = st.dictionaries(_KEYS, st.text(st.characters(exclude_categories=("Cs",)), max_size=16), max_size=6)


@given(fields=_HEADERS)
def test_headers_round_trip(fields: dict[str, str]) -> None:
    assert decode_header(encode_header(fields)) == fields


@given(junk=st.binary(max_size=64))
def test_any_bytes_decode_as_a_header_or_say_why(junk: bytes) -> None:
    for data in (junk, struct.pack("<I", len(junk)) + junk):
        try:
            decode_header(data)
        except TcprosError:
            pass


@given(fields=_HEADERS, trailing=st.binary(max_size=16), cuts=st.lists(st.integers(1, 8), max_size=10))
def test_a_header_split_anywhere_reads_the_same(fields: dict[str, str], trailing: bytes, cuts: list[int]) -> None:
    stream = encode_header(fields) + trailing
    reader = tcpros.HeaderReader()
    got = None
    pos = 0
    for size in [*cuts, len(stream)]:
        piece, pos = stream[pos:pos + size], pos + size
        if piece:
            got = reader.feed(piece)
        if got is not None:
            break
    assert got == fields
    assert bytes(reader.trailing) + stream[pos:] == trailing


@given(frames=st.lists(st.binary(max_size=300), max_size=8), cuts=st.lists(st.integers(1, 200), max_size=20))
def test_frames_split_anywhere_come_out_whole(frames: list[bytes], cuts: list[int]) -> None:
    stream = b"".join(tcpros.encode_frame(f) for f in frames)
    reader = tcpros.FrameReader(max_frame=1000)
    out: list[bytes] = []
    pos = 0
    for size in [*cuts, len(stream)]:
        out += [bytes(f) for f in reader.feed(stream[pos:pos + size])]
        pos += size
    assert out == frames and reader.pending == 0


@given(length=st.integers(1001, 2**32 - 1), rest=st.binary(max_size=8))
def test_a_frame_over_the_limit_is_refused_before_it_is_read(length: int, rest: bytes) -> None:
    reader = tcpros.FrameReader(max_frame=1000)
    try:
        reader.feed(struct.pack("<I", length) + rest)
    except TcprosError as exc:
        assert f"frame of {length} bytes refused" in str(exc)
    else:
        raise AssertionError("accepted")


@given(value=XMLRPC_VALUES)
def test_xmlrpc_values_round_trip(value: object) -> None:
    assert xmlrpc.decode_response(xmlrpc.encode_response(value)) == value
    assert xmlrpc.decode_request(xmlrpc.encode_request("m", [value])) == ("m", [value])


@given(method=st.from_regex(r"[A-Za-z_.]{1,12}", fullmatch=True), text=XML_TEXT)
def test_faults_round_trip(method: str, text: str) -> None:
    try:
        xmlrpc.decode_response(xmlrpc.encode_fault(7, text))
    except xmlrpc.Fault as fault:
        assert (fault.code, fault.message) == (7, text)


@given(junk=st.binary(max_size=120) | st.text(max_size=120).map(str.encode))
def test_any_bytes_decode_as_xmlrpc_or_say_why(junk: bytes) -> None:
    for decode in (xmlrpc.decode_request, xmlrpc.decode_response):
        try:
            decode(junk)
        except xmlrpc.XmlRpcError:
            pass


@given(value=XMLRPC_VALUES, cut=st.integers(0, 400))
def test_a_truncated_xmlrpc_body_is_malformed(value: object, cut: int) -> None:
    body = xmlrpc.encode_response(value)
    if cut < len(body.rstrip()):  # at least the closing ">" is gone
        try:
            xmlrpc.decode_response(body[:cut])
        except xmlrpc.XmlRpcError:
            return
        raise AssertionError("a truncated body was accepted")
