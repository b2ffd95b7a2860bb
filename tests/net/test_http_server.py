"""kame.net's HTTP server and XML-RPC client on 127.0.0.1, with a trivial handler."""

from __future__ import annotations

import asyncio
import re
import socket
import time
from collections.abc import Iterator

import pytest

from kame.net import xmlrpc_client
from kame.net.http_server import HttpRequest, HttpResponse, HttpServer, ServerLimits
from kame.protocol.xmlrpc import Fault, encode_fault, encode_response

from ..support import LoopThread, SilentPeer


def echo(req: HttpRequest) -> HttpResponse:
    if req.path == "/boom":
        raise RuntimeError("handler bug")
    if req.path == "/fault":
        return HttpResponse(200, encode_fault(3, "no"))
    if req.path == "/rpc":
        return HttpResponse(200, encode_response([1, "", req.body.decode()[:10]]))
    return HttpResponse(200, req.method.encode() + b" " + req.path.encode() + b" " + req.body)


@pytest.fixture
def server() -> Iterator[tuple[HttpServer, LoopThread]]:
    loop = LoopThread()
    srv = HttpServer(echo, "127.0.0.1", 0, ServerLimits(max_body=1000, max_receiving=1500, idle_timeout=1.0))
    loop.run(srv.start())
    try:
        yield srv, loop
    finally:
        loop.run(srv.close())
        loop.close()


def test_pipelined_requests_answered_in_order(server: tuple[HttpServer, LoopThread]) -> None:
    srv, _ = server
    reqs = b"".join(b"POST /%s HTTP/1.1\r\nContent-Length: 1\r\n\r\nx" % p for p in (b"a", b"b", b"c"))
    with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:
        s.sendall(reqs)
        out = b""
        while not out.endswith(b"/c x"):
            out += s.recv(65536)
    assert re.findall(rb"POST /\w x", out) == [b"POST /a x", b"POST /b x", b"POST /c x"]


def test_http10_closes_and_handler_errors_are_500(server: tuple[HttpServer, LoopThread]) -> None:
    srv, _ = server
    with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:
        s.sendall(b"POST /x HTTP/1.0\r\nContent-Length: 0\r\n\r\n")
        out = b""
        while chunk := s.recv(65536):
            out += chunk
    assert out.startswith(b"HTTP/1.0 200 OK") and b"Connection: close" in out
    with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:
        s.sendall(b"POST /boom HTTP/1.1\r\nContent-Length: 0\r\n\r\n")
        assert s.recv(65536).startswith(b"HTTP/1.1 500 ")


def test_receive_budget_is_shared(server: tuple[HttpServer, LoopThread]) -> None:
    srv, _ = server
    a = socket.create_connection(("127.0.0.1", srv.port), timeout=3)
    a.sendall(b"POST / HTTP/1.1\r\nContent-Length: 900\r\n\r\npartial")
    b = socket.create_connection(("127.0.0.1", srv.port), timeout=3)
    b.sendall(b"POST / HTTP/1.1\r\nContent-Length: 900\r\n\r\n")
    assert b.recv(100).startswith(b"HTTP/1.1 503 ")
    a.sendall(b"x" * 893)
    assert a.recv(100).startswith(b"HTTP/1.1 200 ")
    a.close()
    b.close()


def test_client_call_fault_and_errors(server: tuple[HttpServer, LoopThread]) -> None:
    srv, loop = server
    base = f"http://127.0.0.1:{srv.port}"
    assert loop.run(xmlrpc_client.call(base + "/rpc", "m", ["a"], 2)) == [1, "", "<?xml vers"]
    with pytest.raises(Fault):
        loop.run(xmlrpc_client.call(base + "/fault", "m", [], 2))
    with pytest.raises(xmlrpc_client.HttpError):
        loop.run(xmlrpc_client.post(base + "/rpc", b"x" * 5000, 2))  # 413 from the server
    with pytest.raises(xmlrpc_client.HttpError):
        loop.run(xmlrpc_client.post("rosrpc://h:1", b"", 2))


def test_client_times_out_on_a_silent_peer() -> None:
    peer = SilentPeer()
    try:
        with pytest.raises(asyncio.TimeoutError):
            asyncio.run(xmlrpc_client.call(peer.uri, "getPid", ["/x"], 0.3))
    finally:
        peer.close()


def test_client_refused_connection() -> None:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with pytest.raises(OSError):
        asyncio.run(xmlrpc_client.call(f"http://127.0.0.1:{port}/", "getPid", ["/x"], 2))


def _read_until(s: socket.socket, tail: bytes) -> bytes:
    out = b""
    while not out.endswith(tail):
        chunk = s.recv(65536)
        assert chunk, out
        out += chunk
    return out


def test_requests_split_anywhere_and_heads_reused(server: tuple[HttpServer, LoopThread]) -> None:
    # Requests arriving whole are parsed from the segment itself, split ones from the buffer;
    # equal heads are parsed once and shared. Each way must give the same answers.
    srv, _ = server
    one = b"POST /p HTTP/1.1\r\nContent-Length: 3\r\n\r\n"
    stream = one + b"abc" + one + b"def" + b"POST /q HTTP/1.1\r\nContent-Length: 3\r\n\r\nghi"
    for cut in range(len(stream) + 1):
        with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:
            s.sendall(stream[:cut])
            time.sleep(0.002)
            s.sendall(stream[cut:])
            out = _read_until(s, b"/q ghi")
        assert re.findall(rb"POST /\w [a-z]{3}", out) == [b"POST /p abc", b"POST /p def", b"POST /q ghi"], cut
    with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:  # byte by byte
        for i in range(len(stream)):
            s.sendall(stream[i : i + 1])
        assert re.findall(rb"POST /\w [a-z]{3}", _read_until(s, b"/q ghi")) == [
            b"POST /p abc", b"POST /p def", b"POST /q ghi"]


def test_head_cache_is_bounded(server: tuple[HttpServer, LoopThread]) -> None:
    srv, _ = server
    with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:
        for i in range(600):
            s.sendall(b"POST /%d HTTP/1.1\r\nContent-Length: 1\r\n\r\nx" % i)
            _read_until(s, b"/%d x" % i)
        s.sendall(b"POST /big HTTP/1.1\r\nX: " + b"a" * 2000 + b"\r\nContent-Length: 1\r\n\r\nx")
        _read_until(s, b"/big x")
    assert 0 < len(srv._heads) <= 256
    assert not any(len(h) > 1024 for h in srv._heads)


def test_partial_request_times_out_after_served_ones() -> None:
    # Requests that arrive whole set no request deadline; one left incomplete still gets 408.
    loop = LoopThread()
    srv = HttpServer(echo, "127.0.0.1", 0, ServerLimits(idle_timeout=5.0, request_timeout=0.3))
    loop.run(srv.start())
    try:
        with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:
            for _ in range(3):
                s.sendall(b"POST /a HTTP/1.1\r\nContent-Length: 1\r\n\r\nx")
                _read_until(s, b"/a x")
            t0 = time.monotonic()
            s.sendall(b"POST /a HTTP/1.1\r\nContent-Length: 1\r\n\r\nxPOST /b HTTP/1.1\r\nContent-Le")
            _read_until(s, b"/a x")
            time.sleep(0.1)
            s.sendall(b"ngth: 5\r\n\r\nab")  # more bytes do not extend the request's deadline
            assert _read_until(s, b"\r\n\r\n").startswith(b"HTTP/1.1 408 ")
            assert 0.25 < time.monotonic() - t0 < 2
    finally:
        loop.run(srv.close())
        loop.close()


def test_clients_stalled_mid_request_cannot_lock_others_out(caplog: pytest.LogCaptureFixture) -> None:
    # Only idle connections were closed to make room: max_connections clients that each start a
    # request and stall got every further caller refused (reset) until their request_timeout.
    import logging

    loop = LoopThread()
    srv = HttpServer(echo, "127.0.0.1", 0, ServerLimits(max_connections=20, request_timeout=30.0))
    loop.run(srv.start())
    stalled: list[socket.socket] = []
    try:
        with caplog.at_level(logging.WARNING, logger="kame.net.http"):
            for _ in range(60):
                s = socket.create_connection(("127.0.0.1", srv.port), timeout=3)
                s.sendall(b"POST /a HTTP/1.1\r\nContent-Length: 100\r\n\r\nab")
                stalled.append(s)
            time.sleep(0.2)
            with socket.create_connection(("127.0.0.1", srv.port), timeout=3) as s:
                s.sendall(b"POST /ok HTTP/1.1\r\nContent-Length: 2\r\n\r\nhi")
                assert _read_until(s, b"/ok hi").startswith(b"HTTP/1.1 200 ")
        lines = [r.getMessage() for r in caplog.records if "to make room" in r.getMessage()]
        assert 1 <= len(lines) <= 3, lines  # 41 closed, a line or two said so
    finally:
        for s in stalled:
            s.close()
        loop.run(srv.close())
        loop.close()


def test_answers_carry_the_servers_date_and_the_client_reads_it(server: tuple[HttpServer, LoopThread]) -> None:
    import time

    from kame.net.xmlrpc_client import XmlRpcProxy
    from kame.protocol.http import parse_date

    srv, _ = server
    proxy = XmlRpcProxy(f"http://127.0.0.1:{srv.port}/rpc")
    try:
        before = int(time.time())
        proxy.call("m")
        after = time.time()
        assert proxy.last_date is not None
        date = parse_date(proxy.last_date)
        assert date is not None and before <= date <= after
    finally:
        proxy.close()


def test_uris_are_read_as_urlsplit_reads_them() -> None:
    from urllib.parse import urlsplit

    from kame.net.xmlrpc_client import _split

    for uri in ("http://127.0.0.1:11311/", "http://127.0.0.1:11311", "http://Robot-1.local:40123/",
                "http://[::1]:11311/", "http://[FE80::1]:80/RPC2", "http://host:0/", "http://h_1:65535/a/b;c",
                "http://robot:11311/path%20x", "HTTP://ROBOT:11311/", "http://robot/", "http://user@robot:1/",
                "http://robot:11311/?q=1", "http://robot:11311/#f", "http://robot:011311/"):
        parts = urlsplit(uri)
        assert _split(uri) == (parts.hostname, parts.port or 80, parts.path or "/"), uri
    for bad in ("http://robot:99999/", "http://robot:x1/"):
        with pytest.raises(ValueError):
            _ = urlsplit(bad).port
        with pytest.raises(ValueError):
            _split(bad)
