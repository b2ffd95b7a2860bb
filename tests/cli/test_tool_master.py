"""The graph tools' master access (kame.cli._tool.Master): what the user is told when a call fails."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from kame.cli._tool import NO_MASTER, Master, ToolError
from tests.support import free_port


@pytest.fixture
def faulting_master() -> Iterator[str]:
    """A master that answers every call with an XML-RPC fault (as a master may refuse a value)."""
    server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=False)

    def refuse(*args: object) -> object:
        raise ValueError("XML-RPC value nested too deeply")

    server.register_function(refuse, "getParam")
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


def test_a_fault_is_reported_as_what_the_master_said(faulting_master: str) -> None:
    with pytest.raises(ToolError) as caught:
        Master("/rosparam", faulting_master).call("getParam", "/x")
    assert str(caught.value) == "the master refused getParam: <class 'ValueError'>:XML-RPC value nested too deeply"


def test_no_master_is_unable_to_communicate() -> None:
    with pytest.raises(ToolError) as caught:
        Master("/rosparam", f"http://127.0.0.1:{free_port()}/").call("getParam", "/x")
    assert str(caught.value) == NO_MASTER
