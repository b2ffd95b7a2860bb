"""kame.net's threaded XML-RPC server (a node's slave API) against stalling and hostile clients."""

from __future__ import annotations

import logging
import socket
import time
from collections.abc import Iterator

import pytest

from kame.net import rpc_server
from kame.net.rpc_server import RpcServer


def _post(port: int, body: bytes = b"ping", timeout: float = 5.0) -> bytes:
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as sock:
        sock.sendall(b"POST / HTTP/1.1\r\nContent-Length: %d\r\nConnection: close\r\n\r\n" % len(body) + body)
        reply = b""
        while chunk := sock.recv(65536):
            reply += chunk
        return reply


@pytest.fixture
def server() -> Iterator[RpcServer]:
    srv = RpcServer("127.0.0.1", 0, lambda body: b"echo " + body)
    srv.start()
    try:
        yield srv
    finally:
        srv.close()


def test_a_full_house_of_stalled_clients_does_not_lock_others_out(server: RpcServer,
                                                                  caplog: pytest.LogCaptureFixture) -> None:
    # MAX_CONNECTIONS clients that send half a request and stall used to fill the server: every
    # further caller (the master's publisherUpdate among them) was refused for IDLE_TIMEOUT.
    stalled = []
    with caplog.at_level(logging.WARNING, logger="kame.net.rpc"):
        for _ in range(rpc_server.MAX_CONNECTIONS + 50):
            sock = socket.create_connection(("127.0.0.1", server.port), timeout=5)
            sock.sendall(b"POST / HTTP/1.1\r\nContent-Le")
            stalled.append(sock)
        deadline = time.monotonic() + 10  # until the accept thread has evicted (and logged)
        while not any("too many XML-RPC connections" in r.getMessage() for r in caplog.records):
            assert time.monotonic() < deadline, "no eviction logged"
            time.sleep(0.02)
        time.sleep(0.2)  # room for any further lines, which the next assert bounds
    # 50 evictions, but not 50 lines
    assert 1 <= sum("too many XML-RPC connections" in r.getMessage() for r in caplog.records) <= 3
    try:
        time.sleep(0.2)
        for _ in range(3):
            assert _post(server.port).endswith(b"echo ping")
        # the quietest stalled clients were closed to make room
        stalled[0].settimeout(2)
        assert stalled[0].recv(100) == b""
    finally:
        for sock in stalled:
            sock.close()


def test_a_request_trickling_in_is_cut_off(server: RpcServer, monkeypatch: pytest.MonkeyPatch) -> None:
    # Bytes every little while used to keep a request (and its thread) alive forever: the idle
    # timeout was per recv. A started request must now arrive within REQUEST_TIMEOUT.
    monkeypatch.setattr(rpc_server, "REQUEST_TIMEOUT", 0.5)
    with socket.create_connection(("127.0.0.1", server.port), timeout=5) as sock:
        sock.sendall(b"POST / HTTP/1.1\r\nContent-Length: 100\r\n\r\n")
        start = time.monotonic()
        closed = False
        while time.monotonic() - start < 6:
            try:
                sock.sendall(b"x")
            except OSError:
                closed = True
                break
            sock.settimeout(0.1)
            try:
                if sock.recv(100) == b"":
                    closed = True
                    break
            except TimeoutError:
                pass
            except OSError:  # closed with our bytes unread: the peer's stack answers with a reset
                closed = True
                break
        assert closed and time.monotonic() - start < 5  # 0.5 s allowed; trickling all of it takes 10 s
    assert _post(server.port).endswith(b"echo ping")


@pytest.mark.parametrize("head", [
    b"\x00\x01\x02garbage\r\n\r\n",
    b"POST / HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\n",
    b"POST / HTTP/1.1\r\nContent-Length: -5\r\n\r\n",
    b"POST / HTTP/1.1\r\nContent-Length: x\r\n\r\n",
    b"POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n",
    b"POST / HTTP/1.1\r\n" + b"X: y\r\n" * 20000,
])
def test_bad_http_is_refused_and_serving_goes_on(server: RpcServer, head: bytes) -> None:
    with socket.create_connection(("127.0.0.1", server.port), timeout=5) as sock:
        sock.sendall(head)
        assert sock.recv(1000).split(b" ")[1] in (b"400", b"411", b"413", b"431")
    assert _post(server.port).endswith(b"echo ping")


def test_answers_carry_the_servers_date_for_roswtfs_clock_check(server: RpcServer) -> None:
    import time
    from email.utils import parsedate_to_datetime

    before = int(time.time())
    reply = _post(server.port)
    after = time.time()
    [date] = [line.split(b": ", 1)[1] for line in reply.split(b"\r\n") if line.startswith(b"Date: ")]
    assert before <= parsedate_to_datetime(date.decode()).timestamp() <= after
