"""An accept loop out of file descriptors pauses before retrying, and its owner's close ends the pause."""

from __future__ import annotations

import errno
import socket
import threading

import pytest

from kame.net.stream import AcceptStarvation


def test_stop_ends_the_pause_at_once(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(AcceptStarvation, "PAUSE", 3600.0)  # a sleep would outlive the test run
    with socket.socket() as sock:
        starved = AcceptStarvation(sock)
        pausing = threading.Thread(target=starved.failed, args=(OSError(errno.EMFILE, "Too many open files"),),
                                   daemon=True)
        pausing.start()
        starved.stop()
        pausing.join(timeout=10.0)
        assert not pausing.is_alive()
