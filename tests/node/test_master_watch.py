"""MasterWatch: a changed master PID, or a master answering again after failing to, means
registering again; the same master answering does not."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from kame.node.master_watch import MasterWatch


class PidMaster:
    """A master that only answers getPid, with a PID the test sets (None: the call fails)."""

    def __init__(self) -> None:
        self.pid: int | None = 100
        self.server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False)
        self.server.register_function(self.getPid, "getPid")
        self.uri = f"http://127.0.0.1:{self.server.server_address[1]}/"
        self.thread = threading.Thread(target=self.server.serve_forever, kwargs={"poll_interval": 0.05})
        self.thread.start()

    def getPid(self, caller_id: str) -> list[object]:
        if self.pid is None:
            return [-1, "down", 0]
        return [1, "", self.pid]

    def close(self) -> None:
        self.server.shutdown()
        self.thread.join(5)
        self.server.server_close()


@pytest.fixture
def master() -> Iterator[PidMaster]:
    m = PidMaster()
    yield m
    m.close()


def test_registers_again_when_the_pid_changes_or_the_master_comes_back(master: PidMaster) -> None:
    calls: list[int | None] = []
    watch = MasterWatch(master.uri, "/n", lambda: calls.append(master.pid))
    watch.check()
    watch.check()
    assert calls == []  # the same master: nothing to do
    master.pid = 200
    watch.check()
    assert calls == [200]
    master.pid = None
    watch.check()
    watch.check()
    assert calls == [200]
    master.pid = 200  # the same PID after failing: registered again, it may have lost us
    watch.check()
    assert calls == [200, 200]


def test_the_watch_thread_ends_at_close(master: PidMaster) -> None:
    import time

    watch = MasterWatch(master.uri, "/n", lambda: None, interval=0.01)
    thread = threading.Thread(target=watch.run)
    thread.start()
    deadline = time.monotonic() + 5
    while watch.pid != 100 and time.monotonic() < deadline:
        time.sleep(0.01)
    assert watch.pid == 100
    watch.close()
    thread.join(5)
    assert not thread.is_alive()
