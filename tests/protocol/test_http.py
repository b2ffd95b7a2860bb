"""kame.protocol.http: HTTP/1.1 requests and responses as bytes, without sockets."""

from __future__ import annotations

import pytest

from kame.protocol.http import (
    HttpError,
    Refusal,
    Request,
    RequestReader,
    ResponseReader,
    date_header,
    encode_request,
    encode_response,
    new_head_cache,
    parse_date,
)


def _requests(reader: RequestReader) -> list[Request | Refusal]:
    out: list[Request | Refusal] = []
    while (event := reader.next_request()) is not None:
        out.append(event)
    return out


def test_pipelined_requests_come_out_in_order_whole_or_byte_by_byte() -> None:
    stream = (b"POST /a HTTP/1.1\r\nContent-Length: 3\r\n\r\nabc"
              b"POST /b HTTP/1.1\r\nContent-Length: 0\r\n\r\n"
              b"POST /c HTTP/1.0\r\nContent-Length: 2\r\nConnection: keep-alive\r\n\r\nhi")
    whole = RequestReader()
    whole.feed(stream)
    trickled = RequestReader()
    got: list[Request | Refusal] = []
    for i in range(len(stream)):
        trickled.feed(stream[i:i + 1])
        got += _requests(trickled)
    for events in (_requests(whole), got):
        assert [(r.path, r.body, r.version, r.keep_alive) for r in events if isinstance(r, Request)] == [
            ("/a", b"abc", "HTTP/1.1", True), ("/b", b"", "HTTP/1.1", True), ("/c", b"hi", "HTTP/1.0", True)]
    assert whole.pending == 0 and trickled.pending == 0


def test_pending_and_body_wanted_follow_a_request_under_way() -> None:
    reader = RequestReader()
    reader.feed(b"POST / HTTP/1.1\r\nContent-Le")
    assert reader.next_request() is None and reader.pending and reader.body_wanted == 0
    reader.feed(b"ngth: 5\r\n\r\nab")
    assert reader.next_request() is None and reader.body_wanted == 5
    reader.feed(bytearray(b"cde"))
    request = reader.next_request()
    assert isinstance(request, Request) and request.body == b"abcde" and type(request.body) is bytes
    assert reader.pending == 0 and reader.body_wanted == 0


@pytest.mark.parametrize(("head", "status"), [
    (b"NONSENSE\r\n\r\n", 400),
    (b"\x00\x01\x02garbage\r\n\r\n", 400),
    (b"POST / HTTP/2.0\r\n\r\n", 505),
    (b"POST / HTTP/1.1\r\nno colon\r\n\r\n", 400),
    (b"POST / HTTP/1.1\r\nContent-Length: x\r\n\r\n", 400),
    (b"POST / HTTP/1.1\r\nContent-Length: -5\r\n\r\n", 400),
    (b"POST / HTTP/1.1\r\nContent-Length: 1001\r\n\r\n", 413),
    (b"POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n", 411),
    (b"POST / HTTP/1.1\r\nX: " + b"a" * 3000, 431),
    (b"POST / HTTP/1.1\r\nX: " + b"a" * 3000 + b"\r\n\r\n", 431),
])
def test_bad_requests_are_refused_with_their_status_and_end_the_stream(head: bytes, status: int) -> None:
    reader = RequestReader(max_header=2048, max_body=1000)
    reader.feed(head)
    refusal = reader.next_request()
    assert isinstance(refusal, Refusal) and refusal.status == status
    reader.feed(b"POST / HTTP/1.1\r\n\r\n")
    assert reader.next_request() is None


@pytest.mark.parametrize(("version", "connection", "keep_alive"), [
    ("HTTP/1.1", "", True), ("HTTP/1.1", "Connection: close\r\n", False),
    ("HTTP/1.0", "", False), ("HTTP/1.0", "Connection: Keep-Alive\r\n", True),
])
def test_keep_alive_as_http_says(version: str, connection: str, keep_alive: bool) -> None:
    reader = RequestReader()
    reader.feed(f"POST / {version}\r\n{connection}\r\n".encode())
    request = reader.next_request()
    assert isinstance(request, Request) and request.keep_alive is keep_alive


def test_a_repeated_head_is_parsed_once_for_all_readers_sharing_a_cache() -> None:
    heads = new_head_cache()
    one, two = RequestReader(heads=heads), RequestReader(heads=heads)
    for reader in (one, two):
        reader.feed(b"POST /x HTTP/1.1\r\nContent-Type: text/xml\r\nContent-Length: 1\r\n\r\nz")
    a, b = one.next_request(), two.next_request()
    assert isinstance(a, Request) and isinstance(b, Request)
    assert a.headers is b.headers and dict(a.headers) == {"content-type": "text/xml", "content-length": "1"}
    assert len(heads) == 1


def test_response_bytes_as_rosmaster_writes_them() -> None:
    assert encode_response(200, b"<x/>") == (
        b"HTTP/1.1 200 OK\r\nContent-type: text/xml\r\nContent-length: 4\r\n\r\n<x/>")
    assert encode_response(413, b"", "text/plain", keep_alive=False) == (
        b"HTTP/1.1 413 Payload Too Large\r\nContent-type: text/plain\r\nContent-length: 0\r\nConnection: close\r\n\r\n")
    assert encode_response(200, b"", version="HTTP/1.0", keep_alive=False).startswith(b"HTTP/1.0 200 OK\r\n")


def test_request_bytes() -> None:
    assert encode_request("h", 11311, "/", b"<m/>") == (
        b"POST / HTTP/1.1\r\nHost: h:11311\r\nUser-Agent: kame\r\nContent-Type: text/xml\r\n"
        b"Content-Length: 4\r\n\r\n<m/>")
    assert b"Connection: close\r\n\r\n" in encode_request("h", 1, "", b"", keep_alive=False)


def test_client_and_server_wired_in_memory() -> None:
    server = RequestReader()
    server.feed(encode_request("127.0.0.1", 8, "/RPC2", b"<call/>"))
    request = server.next_request()
    assert isinstance(request, Request)
    assert (request.method, request.path, request.body) == ("POST", "/RPC2", b"<call/>")
    client = ResponseReader()
    wire = encode_response(200, b"<answer/>", version=request.version, keep_alive=request.keep_alive)
    assert client.feed(wire[:10]) is None
    assert client.feed(wire[10:]) == b"<answer/>" and client.keep_alive


def test_response_reader_cases() -> None:
    closing = ResponseReader()
    assert closing.feed(b"HTTP/1.0 200 OK\r\n\r\npart one ") is None
    assert closing.feed(b"and two") is None
    assert closing.feed_eof() == b"part one and two" and not closing.keep_alive
    told = ResponseReader()
    assert told.feed(b"HTTP/1.1 200 OK\r\nContent-Length: 2\r\nConnection: close\r\n\r\nok") == b"ok"
    assert not told.keep_alive
    with pytest.raises(HttpError, match="500"):
        ResponseReader().feed(b"HTTP/1.1 500 Internal Server Error\r\nContent-Length: 0\r\n\r\n")
    with pytest.raises(HttpError, match="too large"):
        ResponseReader(max_body=10).feed(b"HTTP/1.1 200 OK\r\nContent-Length: 11\r\n\r\n")
    with pytest.raises(HttpError, match="head too large"):
        ResponseReader(max_header=100).feed(b"HTTP/1.1 200 OK\r\n" + b"X: y\r\n" * 50)
    short = ResponseReader()
    assert short.feed(b"HTTP/1.1 200 OK\r\nContent-Length: 9\r\n\r\nabc") is None
    with pytest.raises(HttpError, match="cut short"):
        short.feed_eof()
    with pytest.raises(HttpError, match="before the response"):
        ResponseReader().feed_eof()


def test_no_other_module_speaks_http_or_sets_process_wide_socket_defaults() -> None:
    # kame's servers and clients go through this module; the stdlib's HTTP stacks and
    # socket.setdefaulttimeout (which changes every socket of the process) are not used in kame.
    # rostest.get_master keeps returning xmlrpc.client.ServerProxy: that is rostest's API.
    import re
    from pathlib import Path

    import kame

    banned = re.compile(r"setdefaulttimeout|^\s*(import|from)\s+(xmlrpc|http)\.(client|server)\b", re.M)
    root = Path(kame.__file__).parent
    # kame.net.xmlrpc_servers is the one exception: the stdlib's XML-RPC server classes themselves, as
    # rosgraph.xmlrpc's API hands them to ROS code that builds its own server; kame serves through none
    # of them (nothing in kame imports that module: the second assertion)
    api_for_users = "net/xmlrpc_servers.py"
    offenders = [str(path.relative_to(root)) for path in sorted(root.rglob("*.py")) if banned.search(path.read_text())]
    assert offenders == [api_for_users]
    assert not [str(path.relative_to(root)) for path in sorted(root.rglob("*.py"))
                if "xmlrpc_servers" in path.read_text() and str(path.relative_to(root)) != api_for_users]


def test_a_response_carries_the_date_it_is_given_and_the_reader_keeps_it() -> None:
    line = date_header(784111777)
    assert line == b"Date: Sun, 06 Nov 1994 08:49:37 GMT\r\n"  # RFC 9110's example
    data = encode_response(200, b"<x/>", date=line)
    assert data == (b"HTTP/1.1 200 OK\r\nDate: Sun, 06 Nov 1994 08:49:37 GMT\r\nContent-type: text/xml\r\n"
                    b"Content-length: 4\r\n\r\n<x/>")
    reader = ResponseReader()
    assert reader.feed(data) == b"<x/>"
    assert reader.date == "Sun, 06 Nov 1994 08:49:37 GMT" and parse_date(reader.date) == 784111777
    plain = ResponseReader()
    assert plain.feed(encode_response(200, b"")) == b"" and plain.date is None
    for bad in ("", "yesterday", "Sun, 06 Nov 1994 08:49:37"):  # the last: no zone
        assert parse_date(bad) is None


def test_the_date_line_is_what_the_standard_library_writes() -> None:
    from email.utils import formatdate  # what Python's http.server (so rosmaster and rospy) sends

    leap_days = (951782400, 951868799.5, 1709164800, 4107542400)  # 2000-02-29 (twice), 2024-02-29, 2100-03-01
    spread = range(0, 4_200_000_000, 7_777_777)  # 1970 to 2103, every weekday, month and hour
    for seconds in (0, 59.999, 4102444799, 784111777 + 86400 * 7 * 13, *leap_days, *spread):
        assert date_header(seconds) == f"Date: {formatdate(seconds, usegmt=True)}\r\n".encode()
        assert parse_date(date_header(seconds)[6:-2].decode()) == int(seconds)
