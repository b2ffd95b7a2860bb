"""kame.net's HTTP server and XML-RPC client on 127.0.0.1, with a trivial handler."""

from __future__ import annotations

import asyncio
import re
import socket
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
