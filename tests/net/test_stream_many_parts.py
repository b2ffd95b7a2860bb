"""A frame of more buffers than one sendmsg takes (the kernel's IOV_MAX is 1024): a large
message serialized piece by piece, such as amcl's particle cloud, goes out whole."""

from __future__ import annotations

import socket

from kame.net.stream import Flusher, Sender
from tests.net.test_stream import read_all


def test_a_frame_of_thousands_of_parts_is_sent_whole() -> None:
    flusher = Flusher()
    a, b = socket.socketpair()
    failures: list[BaseException] = []
    try:
        sender = Sender(a, flusher, 10, failures.append)
        parts = [bytes([i % 256]) * 7 for i in range(3000)]
        sender.send_parts(parts)
        assert read_all(b, 7 * 3000) == b"".join(parts)
        assert not failures
    finally:
        flusher.close()
        a.close()
        b.close()
