"""rosmaster.master.Master in this process: serves the master API until stopped."""

from __future__ import annotations

import pytest

import rosgraph
from rosmaster.master import Master

from ..support import free_port


def test_master_in_process_serves_until_stopped() -> None:
    master = Master(port=0)
    master.start()
    try:
        assert master.ok() and master.port > 0 and master.uri is not None
        uri = f"http://127.0.0.1:{master.port}/"
        handle = rosgraph.Master("/tester", master_uri=uri)
        handle.setParam("/x", 5)
        assert handle.getParam("/x") == 5 and handle.getUri() == master.uri
    finally:
        master.stop()
    assert not master.ok()
    assert not rosgraph.is_master_online(uri)


def test_a_taken_port_is_an_error_and_leaves_nothing_running() -> None:
    first = Master(port=free_port())
    first.start()
    try:
        second = Master(port=first.port)
        with pytest.raises(OSError):
            second.start()
        assert not second.ok()
    finally:
        first.stop()
