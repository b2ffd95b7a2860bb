"""MasterWatch: a master that does not know the node (a new one) means registering again; one
that knows it, or does not answer, does not; a node that registered nothing does nothing."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from kame.node.master_watch import MasterWatch


class LookupMaster:
    """A master that only answers lookupNode: `known` says whether it knows the node, `down`
    makes it fail as a master that has gone (an XML-RPC fault)."""

    def __init__(self) -> None:
        self.known = True
        self.down = False
        self.lookups = 0
        self.server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False)
        self.server.register_function(self.lookupNode, "lookupNode")
        self.uri = f"http://127.0.0.1:{self.server.server_address[1]}/"
        self.thread = threading.Thread(target=self.server.serve_forever, kwargs={"poll_interval": 0.05})
        self.thread.start()

    def lookupNode(self, caller_id: str, name: str) -> list[object]:
        self.lookups += 1
        if self.down:
            raise RuntimeError("gone")
        if self.known:
            return [1, "node api", "http://n:1/"]
        return [-1, f"unknown node [{name}]", ""]

    def close(self) -> None:
        self.server.shutdown()
        self.thread.join(5)
        self.server.server_close()


@pytest.fixture
def master() -> Iterator[LookupMaster]:
    m = LookupMaster()
    yield m
    m.close()


def test_registers_again_only_with_a_master_that_does_not_know_the_node(master: LookupMaster) -> None:
    registrations = [0]
    watch = MasterWatch(master.uri, "/n", lambda: True, lambda: registrations.__setitem__(0, registrations[0] + 1))
    watch.check()
    assert registrations == [0]  # it knows us
    master.down = True
    watch.check()
    assert registrations == [0]  # no answer is no restart
    master.down, master.known = False, False
    watch.check()
    assert registrations == [1]
    master.known = True
    watch.check()
    assert registrations == [1]


def test_a_node_without_registrations_does_not_ask(master: LookupMaster) -> None:
    watch = MasterWatch(master.uri, "/n", lambda: False, lambda: None)
    watch.check()
    assert master.lookups == 0


def test_the_watch_thread_checks_until_closed(master: LookupMaster) -> None:
    watch = MasterWatch(master.uri, "/n", lambda: True, lambda: None, interval=0.01)
    thread = threading.Thread(target=watch.run)
    thread.start()
    deadline = time.monotonic() + 5
    while master.lookups < 2 and time.monotonic() < deadline:
        time.sleep(0.01)
    watch.close()
    thread.join(5)
    assert master.lookups >= 2 and not thread.is_alive()
