"""SimpleActionClient when the server answers before send_goal has returned: the first
transition and feedback must still reach the user's callbacks (actionlib drops them as
"not tracking" when they arrive on another thread before the handle is recorded)."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

import kame.client.action.simple_action_client as simple_module
from actionlib import CommState


class _Handle:
    def get_comm_state(self) -> int:
        return int(CommState.ACTIVE)


class _AnsweringFast:
    """An ActionClient whose server's ACTIVE status and first feedback arrive, on another
    thread, while send_goal is still returning."""

    def __init__(self, ns: str, spec: Any) -> None:
        self.answered: threading.Thread | None = None

    def send_goal(self, goal: Any, transition_cb: Any, feedback_cb: Any) -> _Handle:
        handle = _Handle()

        def answer() -> None:
            transition_cb(handle)
            feedback_cb(handle, "fb")

        self.answered = threading.Thread(target=answer)
        self.answered.start()
        time.sleep(0.2)  # the answer is delivered before we return the handle
        return handle


def test_an_answer_before_send_goal_returns_is_not_lost(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(simple_module, "ActionClient", _AnsweringFast)
    client = simple_module.SimpleActionClient("/x", object)
    events: list[str] = []
    client.send_goal("goal", active_cb=lambda: events.append("active"), feedback_cb=events.append)
    fake = client.action_client
    assert isinstance(fake, _AnsweringFast) and fake.answered is not None
    fake.answered.join(5)
    assert events == ["active", "fb"]
