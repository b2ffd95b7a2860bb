"""kame.net.websocket_listener with the websockets library's own client: the peer check, the
bound on what a client may send, the bounded queue a client that does not read is held to."""

from __future__ import annotations

import shutil
import ssl
import subprocess
import threading
from pathlib import Path

import pytest
from websockets.exceptions import ConnectionClosedError, InvalidStatus
from websockets.sync.client import connect

from kame.net.websocket_listener import Client, Limits, WebSocketListener
from tests.support import wait_until


class Echo:
    def __init__(self, client: Client) -> None:
        self.client = client
        self.closed = threading.Event()

    def on_frame(self, frame: str | bytes) -> None:
        self.client.send(frame)

    def on_close(self) -> None:
        self.closed.set()


def test_frames_go_both_ways_and_close_joins_everything() -> None:
    sessions: list[Echo] = []

    def open_session(client: Client) -> Echo:
        sessions.append(Echo(client))
        return sessions[-1]

    listener = WebSocketListener("127.0.0.1", 0, open_session)
    listener.start()
    try:
        with connect(f"ws://127.0.0.1:{listener.port}") as ws:
            ws.send("hello")
            assert ws.recv(timeout=5) == "hello"
            ws.send(b"\x00\x01")
            assert ws.recv(timeout=5) == b"\x00\x01"
    finally:
        listener.close()
    assert sessions[0].closed.is_set()
    left = [t.name for t in threading.enumerate() if t.name.startswith("kame-ws")]
    assert not left, left


def test_a_refused_peer_gets_403() -> None:
    listener = WebSocketListener("127.0.0.1", 0, Echo, admit=lambda address: False)
    listener.start()
    try:
        with pytest.raises(InvalidStatus) as caught:
            connect(f"ws://127.0.0.1:{listener.port}", open_timeout=5)
        assert caught.value.response.status_code == 403
        assert listener.clients() == []
    finally:
        listener.close()


def test_a_frame_over_the_limit_closes_only_that_client() -> None:
    listener = WebSocketListener("127.0.0.1", 0, Echo, limits=Limits(max_message_size=1000))
    listener.start()
    try:
        with connect(f"ws://127.0.0.1:{listener.port}") as big, connect(f"ws://127.0.0.1:{listener.port}") as other:
            big.send("x" * 2000)
            with pytest.raises(ConnectionClosedError) as caught:
                big.recv(timeout=5)
            assert caught.value.rcvd is not None and caught.value.rcvd.code == 1009
            other.send("still here")
            assert other.recv(timeout=5) == "still here"
    finally:
        listener.close()


def test_a_client_that_does_not_read_is_held_to_its_queue() -> None:
    clients: list[Client] = []

    def open_session(client: Client) -> Echo:
        clients.append(client)
        return Echo(client)

    limits = Limits(max_frames=50, max_bytes=10_000_000)
    listener = WebSocketListener("127.0.0.1", 0, open_session, limits=limits)
    listener.start()
    try:
        with connect(f"ws://127.0.0.1:{listener.port}", max_queue=1, close_timeout=1) as ws:
            assert wait_until(lambda: bool(clients), 5)
            frame = "y" * 100_000
            for _ in range(2000):  # 200 MB offered; the socket buffers hold a few MB at most
                clients[0].send(frame)
                assert clients[0].queued() <= limits.max_frames
            assert clients[0].dropped > 1000
            assert ws.recv(timeout=5) == frame  # and the client still gets the newest ones
            listener.close()  # its sender, blocked on a client that stopped reading, is cut off
    finally:
        listener.close()


def test_wss_with_a_certificate_and_its_key(tmp_path: Path) -> None:
    openssl = shutil.which("openssl")
    if openssl is None:
        pytest.skip("no openssl to make a certificate")
    cert, key = tmp_path / "cert.pem", tmp_path / "key.pem"
    subprocess.run([openssl, "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", str(key), "-out", str(cert),
                    "-days", "1", "-subj", "/CN=127.0.0.1", "-addext", "subjectAltName=IP:127.0.0.1"],
                   check=True, capture_output=True)
    listener = WebSocketListener("127.0.0.1", 0, Echo, tls=(str(cert), str(key)))
    listener.start()
    try:
        trusted = ssl.create_default_context(cafile=str(cert))
        with connect(f"wss://127.0.0.1:{listener.port}", ssl=trusted) as ws:
            ws.send("over TLS")
            assert ws.recv(timeout=5) == "over TLS"
    finally:
        listener.close()
