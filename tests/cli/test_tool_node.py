"""The tools' node (rosbag record/play, rosout): a wait for "this happened, or we were stopped"
ends when the condition is notified, or at once when the tool is stopped (Ctrl-C, SIGTERM, a
master's shutdown request), with no polling in between."""

from __future__ import annotations

import os
import signal
import threading
from collections.abc import Iterator

import pytest

from kame.cli._node import ToolNode


@pytest.fixture
def tool(monkeypatch: pytest.MonkeyPatch) -> Iterator[ToolNode]:
    monkeypatch.setenv("ROS_MASTER_URI", "http://127.0.0.1:1/")
    handlers = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    made = ToolNode({}, "tool_under_test")
    try:
        yield made
    finally:
        made.node.shutdown("test over")
        signal.signal(signal.SIGINT, handlers[0])
        signal.signal(signal.SIGTERM, handlers[1])


def _waiting(tool: ToolNode, ready: list[bool]) -> tuple[threading.Thread, list[bool]]:
    result: list[bool] = []
    thread = threading.Thread(target=lambda: result.append(tool.wait_until(lambda: ready[0])))
    thread.start()
    return thread, result


def test_the_wait_ends_when_its_condition_is_notified(tool: ToolNode) -> None:
    ready = [False]
    thread, result = _waiting(tool, ready)
    ready[0] = True
    tool.notify()
    thread.join(10)
    assert result == [True] and not tool.stop.is_set()


def test_stopping_ends_the_wait(tool: ToolNode) -> None:
    thread, result = _waiting(tool, [False])
    tool.request_stop()
    thread.join(10)
    assert result == [False]


def test_a_signal_stops_the_tool_and_ends_a_wait_in_the_main_thread(tool: ToolNode) -> None:
    # sent to the process, as kill and a terminal's Ctrl-C do: Linux delivers it to the main thread
    threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGTERM)).start()
    assert tool.wait_until(lambda: False) is False
    assert tool.stop.is_set()
