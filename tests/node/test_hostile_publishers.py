"""Publishers that misbehave on purpose or by accident: what a subscriber says, holds and retries.

Each fake publisher is a real node's registration and requestTopic whose TCPROS port is a
socket the test serves by hand (`serve_each`)."""

from __future__ import annotations

import logging
import re
import socket
import struct
import threading
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from kame.net.backoff import RespawnBackoff
from kame.node import publisher_link
from kame.protocol import tcpros
from std_msgs.msg import String

from ..support import wait_until

STRING = ("std_msgs/String", String._md5sum, String._full_text)


Answer = Callable[[socket.socket], None]


@pytest.fixture
def serve_each(make_node: Any) -> Iterator[Callable[[str, str, Answer], list[socket.socket]]]:
    """serve_each(name, topic, answer): a publisher `name` of `topic` whose every TCPROS
    connection gets `answer(conn)` once our header is read; returns the connections as they
    come. Its listener and serving thread end with the test."""
    servers: list[tuple[socket.socket, threading.Thread]] = []

    def start(name: str, topic: str, answer: Answer) -> list[socket.socket]:
        server = socket.socket()
        server.bind(("127.0.0.1", 0))
        server.listen(8)
        fake = make_node(name)
        fake.tcpros_port = server.getsockname()[1]  # before advertising: requestTopic points here
        fake.advertise(topic, *STRING)
        accepted: list[socket.socket] = []

        def serve() -> None:
            while True:
                try:
                    conn, _ = server.accept()
                except OSError:  # the test is over: shutdown() woke the accept
                    return
                accepted.append(conn)
                conn.recv(65536)
                answer(conn)

        thread = threading.Thread(target=serve, name=f"fake-publisher{name}")
        thread.start()
        servers.append((server, thread))
        return accepted

    yield start
    for server, thread in servers:
        server.shutdown(socket.SHUT_RDWR)
        thread.join(10)
        server.close()


def test_a_malformed_reply_header_is_one_error_and_the_retries_back_off(
        make_node: Any, serve_each: Any, caplog: pytest.LogCaptureFixture, monkeypatch: pytest.MonkeyPatch) -> None:
    # The reply used to be retried every 2 s for ever with nothing above a debug line.
    monkeypatch.setattr(publisher_link, "RETRY_DELAY", 0.01)
    monkeypatch.setattr(RespawnBackoff, "START", 0.02)
    garbage = struct.pack("<I", 8) + struct.pack("<I", 4) + b"abcd"  # a field without '='
    accepted = serve_each("/garbler", "/garbled", lambda conn: (conn.sendall(garbage), conn.close()))
    caplog.set_level(logging.DEBUG, logger="kame.topics")
    make_node("/garble_listener").subscribe("/garbled", *STRING, lambda frames, header: None)

    def delays() -> list[float]:
        return [float(r.getMessage().split("trying again in ")[1].split()[0]) for r in caplog.records
                if "malformed connection header from" in r.getMessage()]

    assert wait_until(lambda: len(delays()) >= 5, timeout=10), caplog.text
    assert delays()[:5] == [0.01, 0.02, 0.04, 0.08, 0.16]
    assert len(accepted) >= 5
    errors = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert len(errors) == 1, errors
    assert errors[0].startswith("publisher /garbler of /garbled answered with a malformed connection header "), errors


def reply_header(name: str, topic: str) -> bytes:
    return tcpros.encode_header(tcpros.publisher_reply_fields(callerid=name, topic=topic,
                                                              spec=tcpros.TopicSpec(*STRING)))


def test_a_publisher_that_drops_us_after_each_handshake_is_reconnected_to_ever_more_slowly(
        make_node: Any, serve_each: Any, caplog: pytest.LogCaptureFixture, monkeypatch: pytest.MonkeyPatch) -> None:
    # "Announce 64 MiB, then close" was reconnected to at once, for ever: 1.6 GB in 40 s
    monkeypatch.setattr(RespawnBackoff, "START", 0.02)
    announce = struct.pack("<I", 64 << 20) + b"0123456789"

    def drop(conn: socket.socket) -> None:
        conn.sendall(reply_header("/dropper", "/dropped") + announce)
        conn.close()

    accepted = serve_each("/dropper", "/dropped", drop)
    caplog.set_level(logging.WARNING, logger="kame.topics")
    make_node("/drop_listener").subscribe("/dropped", *STRING, lambda frames, header: None)

    def delays() -> list[float]:
        return [float(r.getMessage().split("connecting again in ")[1].split()[0]) for r in caplog.records
                if "dropped the connection on /dropped" in r.getMessage()]

    assert wait_until(lambda: len(delays()) >= 4, timeout=10), caplog.text
    assert delays()[:4] == [0.02, 0.04, 0.08, 0.16]  # the first drop is retried at once
    first = caplog.records[0].getMessage()
    assert first.startswith("/dropper dropped the connection on /dropped ") and first.endswith(
        " s after it was made, 2 times in a row: connecting again in 0.02 s"), first
    assert len(accepted) >= 5


def test_a_frame_dripped_a_byte_at_a_time_is_cut_off_by_its_deadline(
        make_node: Any, serve_each: Any, caplog: pytest.LogCaptureFixture, monkeypatch: pytest.MonkeyPatch) -> None:
    # Each byte reset the 30 s stall timeout: a frame at a byte every 10 s held its buffer for ever
    from kame.node import topics

    monkeypatch.setattr(topics, "STALL_TIMEOUT", 1.0)  # 20 drips: a loaded machine does not stall one
    monkeypatch.setattr(publisher_link, "MIN_FRAME_RATE", 10_000)  # 1,000 bytes: 0.1 s more
    test_over = threading.Event()
    dropped = threading.Event()

    def drip(conn: socket.socket) -> None:
        conn.sendall(reply_header("/dripper", "/dripped") + struct.pack("<I", 1000) + b"\4\0\0\0")
        try:
            while not test_over.wait(0.05):  # a byte every 0.05 s: the stall timeout never passes
                conn.sendall(b"x")
        except OSError:  # the subscriber hung up
            dropped.set()
        conn.close()

    serve_each("/dripper", "/dripped", drip)
    caplog.set_level(logging.ERROR, logger="kame.topics")
    try:
        make_node("/drip_listener").subscribe("/dripped", *STRING, lambda frames, header: None)
        assert dropped.wait(10)
    finally:
        test_over.set()
    (line,) = [r.getMessage() for r in caplog.records]
    assert re.match(r"dropping the connection to /dripper on /dripped: Stalled: a frame of 1000 bytes is not whole "
                    r"\d+\.\d s into it \(\d+ bytes came\)", line), line
    assert line.endswith("a frame must arrive at 9 KiB/s at least"), line
