"""The roslaunch XML-RPC server tells a call with the wrong arguments from a failure inside."""

from __future__ import annotations

import logging
import xmlrpc.client
from collections.abc import Iterator

import pytest

from kame.launch.server import LaunchServer, ProcessState


def _broken_table() -> list[ProcessState]:
    return sorted([ProcessState("a", 1, True), None])  # type: ignore[list-item]  # TypeError inside


@pytest.fixture
def server() -> Iterator[LaunchServer]:
    launch = LaunchServer("127.0.0.1", "127.0.0.1", _broken_table)
    launch.start()
    try:
        yield launch
    finally:
        launch.close()


def test_wrong_arguments_are_refused_as_such(server: LaunchServer) -> None:
    proxy = xmlrpc.client.ServerProxy(server.uri)
    with pytest.raises(xmlrpc.client.Fault, match="process_info: wrong number or type of arguments"):
        proxy.process_info()
    assert proxy.get_pid()[0] == 1


def test_a_type_error_inside_is_logged_with_its_traceback(server: LaunchServer,
                                                          caplog: pytest.LogCaptureFixture) -> None:
    proxy = xmlrpc.client.ServerProxy(server.uri)
    with caplog.at_level(logging.ERROR), pytest.raises(xmlrpc.client.Fault) as fault:
        proxy.list_processes()
    assert "wrong number" not in fault.value.faultString and "not supported between" in fault.value.faultString
    (record,) = [r for r in caplog.records if "list_processes failed" in r.getMessage()]
    assert record.exc_info is not None and record.exc_info[0] is TypeError
