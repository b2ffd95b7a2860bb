"""A subscriber callback that fails: an error on the console while the node runs; once shutdown
has begun (a callback publishing to a topic just closed), only a line in the log file, as rospy."""

from __future__ import annotations

import logging
from typing import Any

import pytest

from kame.client import core
from kame.client.errors import ROSException
from kame.client.topics import _Callbacks
from std_msgs.msg import String


def publish_to_a_closed_topic(_msg: Any) -> None:
    raise ROSException("publish() to a closed topic")


def deliver(callbacks: _Callbacks) -> None:
    callbacks.deliver_messages([String("scan")], {"callerid": "/stageros"})


def test_a_failing_callback_is_an_error_while_running_and_quiet_at_shutdown(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], caplog: pytest.LogCaptureFixture) -> None:
    callbacks = _Callbacks(String, [(publish_to_a_closed_topic, None, False)])
    deliver(callbacks)
    running = capsys.readouterr()
    assert "bad callback" in running.out + running.err and "publish() to a closed topic" in running.out + running.err

    monkeypatch.setattr(core, "is_shutdown", lambda: True)
    with caplog.at_level(logging.WARNING, logger="rospy.topics"):
        deliver(callbacks)
    stopping = capsys.readouterr()
    assert stopping.out + stopping.err == ""
    assert [r.getMessage().splitlines()[0] for r in caplog.records if r.name == "rospy.topics"] == [
        f"during shutdown, bad callback: {publish_to_a_closed_topic}"]
