"""SimpleActionClient: one goal at a time, seen as PENDING, ACTIVE or DONE (kame.action.simple_state)."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from actionlib_msgs.msg import GoalStatus
from kame.action import CommState as _Comm
from kame.action import SimpleGoalState as _Simple
from kame.action import simple_step
from kame.client import clock, core
from kame.client.action._log import logdebug, logerr
from kame.client.action.action_client import ActionClient, ClientGoalHandle, get_name_of_constant

__all__ = ["SimpleActionClient", "SimpleGoalState"]


class SimpleGoalState:
    PENDING = int(_Simple.PENDING)
    ACTIVE = int(_Simple.ACTIVE)
    DONE = int(_Simple.DONE)

    @classmethod
    def to_string(cls, n: int) -> str:
        return get_name_of_constant(cls, n)


def _seconds(value: Any) -> float:
    if value is None:
        return 0.0
    return float(value.to_sec()) if hasattr(value, "to_sec") else float(value)


class SimpleActionClient:
    def __init__(self, ns: str, ActionSpec: Any) -> None:
        self.action_client = ActionClient(ns, ActionSpec)
        self.simple_state = SimpleGoalState.DONE
        self.gh: ClientGoalHandle | None = None
        self.done_condition = threading.Condition()
        self.done_cb: Callable[[int, Any], Any] | None = None
        self.active_cb: Callable[[], Any] | None = None
        self.feedback_cb: Callable[[Any], Any] | None = None
        # Held while send_goal publishes the goal and records its handle: the server's first
        # status or feedback can arrive on another thread before the handle is recorded, and
        # actionlib then drops it as "not tracking" (no active_cb, a feedback lost). Callbacks
        # wait for the handle instead. Reentrant: a callback on the sending thread passes.
        self._sending = threading.RLock()

    def wait_for_server(self, timeout: Any = None) -> bool:
        return self.action_client.wait_for_server(timeout)

    def send_goal(self, goal: Any, done_cb: Callable[[int, Any], Any] | None = None,
                  active_cb: Callable[[], Any] | None = None,
                  feedback_cb: Callable[[Any], Any] | None = None) -> None:
        """Send `goal` and follow it instead of the previous one (which is not canceled)."""
        self.stop_tracking_goal()
        self.done_cb = done_cb
        self.active_cb = active_cb
        self.feedback_cb = feedback_cb
        self.simple_state = SimpleGoalState.PENDING
        with self._sending:
            self.gh = self.action_client.send_goal(goal, self._handle_transition, self._handle_feedback)

    def send_goal_and_wait(self, goal: Any, execute_timeout: Any = None, preempt_timeout: Any = None) -> int:
        """Send, wait up to execute_timeout, cancel when it runs out and wait up to preempt_timeout."""
        self.send_goal(goal)
        if not self.wait_for_result(execute_timeout):
            logdebug("Canceling goal")
            self.cancel_goal()
            if self.wait_for_result(preempt_timeout):
                logdebug("Preempt finished within specified preempt_timeout [%.2f]", _seconds(preempt_timeout))
            else:
                logdebug("Preempt didn't finish specified preempt_timeout [%.2f]", _seconds(preempt_timeout))
        return self.get_state()

    def wait_for_result(self, timeout: Any = None) -> bool:
        """True once the goal is DONE; False when `timeout` (zero or None: no limit) runs out first."""
        if self.gh is None:
            logerr("Called wait_for_result when no goal exists")
            return False
        seconds = _seconds(timeout)
        deadline = clock.get_rostime() + clock.Duration.from_sec(seconds)
        with self.done_condition:
            while not core.is_shutdown() and self.simple_state != SimpleGoalState.DONE:
                left = (deadline - clock.get_rostime()).to_sec()
                if seconds > 0 and left <= 0:
                    break
                self.done_condition.wait(min(left, 0.1) if seconds > 0 else 0.1)
        return self.simple_state == SimpleGoalState.DONE

    def get_result(self) -> Any:
        if self.gh is None:
            logerr("Called get_result when no goal is running")
            return None
        return self.gh.get_result()

    def get_state(self) -> int:
        """PENDING, ACTIVE or the terminal status (RECALLING reads PENDING, PREEMPTING ACTIVE); LOST
        when no goal is followed."""
        if self.gh is None:
            return int(GoalStatus.LOST)
        status = self.gh.get_goal_status()
        if status == GoalStatus.RECALLING:
            return int(GoalStatus.PENDING)
        if status == GoalStatus.PREEMPTING:
            return int(GoalStatus.ACTIVE)
        return status

    def get_goal_status_text(self) -> str:
        if self.gh is None:
            logerr("Called get_goal_status_text when no goal is running")
            return "ERROR: Called get_goal_status_text when no goal is running"
        return self.gh.get_goal_status_text()

    def cancel_all_goals(self) -> None:
        self.action_client.cancel_all_goals()

    def cancel_goals_at_and_before_time(self, time: Any) -> None:
        self.action_client.cancel_goals_at_and_before_time(time)

    def cancel_goal(self) -> None:
        if self.gh is not None:
            self.gh.cancel()

    def stop_tracking_goal(self) -> None:
        self.gh = None

    def _handle_transition(self, gh: ClientGoalHandle) -> None:
        with self._sending:
            pass  # the goal being sent has its handle recorded
        if gh != self.gh:
            logerr("Got a transition callback on a goal handle that we're not tracking")
            return
        comm = gh.get_comm_state()
        step = simple_step(_Simple(self.simple_state), _Comm(comm))
        if step.error:
            logerr("%s with SimpleActionClient in NS %s", step.error,
                         core.resolve_name(self.action_client.ns))
            return
        if step.call_active:
            self.simple_state = int(step.state)
            if self.active_cb is not None:
                self.active_cb()
        elif step.call_done:
            if self.done_cb is not None:
                self.done_cb(gh.get_goal_status(), gh.get_result())
            with self.done_condition:
                self.simple_state = int(step.state)
                self.done_condition.notify_all()

    def _handle_feedback(self, gh: ClientGoalHandle, feedback: Any) -> None:
        with self._sending:
            pass
        if self.gh is None:
            return  # old feedback between forgetting a goal and sending the next: not an error
        if gh != self.gh:
            logerr("Got a feedback callback on a goal handle that we're not tracking. %s vs %s",
                         self.gh.comm_state_machine.action_goal.goal_id.id,
                         gh.comm_state_machine.action_goal.goal_id.id)
            return
        if self.feedback_cb is not None:
            self.feedback_cb(feedback)
