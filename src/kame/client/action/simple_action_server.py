"""SimpleActionServer: one goal at a time; a newer goal preempts the current one.

With an execute callback, goals run one after another on a thread this server owns (woken
when a goal arrives and at shutdown); without one, the user polls or registers goal and
preempt callbacks and calls accept_new_goal(). Lock order: the ActionServer's lock, then ours.
"""

from __future__ import annotations

import threading
import traceback
from collections.abc import Callable
from typing import Any

from actionlib_msgs.msg import GoalStatus
from kame.client import core
from kame.client.action._log import logdebug, logerr, logwarn
from kame.client.action.action_server import ActionServer
from kame.client.action.server_goal_handle import ServerGoalHandle

_ACCEPTED = "This goal has been accepted by the simple action server"
_SUPERSEDED = "This goal was canceled because another goal was received by the simple action server"


EXECUTE_JOIN_TIMEOUT = 2.0


class SimpleActionServer:
    def __init__(self, name: str, ActionSpec: Any, execute_cb: Callable[[Any], Any] | None = None,
                 auto_start: bool = True) -> None:
        self.new_goal = False
        self.preempt_request = False
        self.new_goal_preempt_request = False
        self.execute_callback = execute_cb
        self.goal_callback: Callable[[], Any] | None = None
        self.preempt_callback: Callable[[], Any] | None = None
        self.need_to_terminate = False
        self.lock = threading.RLock()
        self.execute_condition = threading.Condition(self.lock)
        self.current_goal = ServerGoalHandle()
        self.next_goal = ServerGoalHandle()
        self.execute_thread: threading.Thread | None = None
        if execute_cb is not None:
            self.execute_thread = threading.Thread(target=self.executeLoop, name=f"actionlib-execute {name}",
                                                   daemon=True)
            self.execute_thread.start()
            core.on_shutdown(self._terminate)
        self.action_server = ActionServer(name, ActionSpec, self.internal_goal_callback,
                                          self.internal_preempt_callback, auto_start)

    def _terminate(self) -> None:
        """At shutdown: end the execute loop and join its thread (a goal still running gets a
        bounded wait; its callback sees rospy.is_shutdown())."""
        with self.execute_condition:
            self.need_to_terminate = True
            self.execute_condition.notify_all()
        thread = self.execute_thread
        if thread is not None and thread is not threading.current_thread():
            thread.join(EXECUTE_JOIN_TIMEOUT)

    def start(self) -> None:
        self.action_server.start()

    def accept_new_goal(self) -> Any:
        with self.action_server.lock, self.lock:
            if not self.new_goal or not self.next_goal.get_goal():
                logerr("Attempting to accept the next goal when a new goal is not available")
                return None
            if self.is_active() and self.current_goal.get_goal() and self.current_goal != self.next_goal:
                self.current_goal.set_canceled(None, _SUPERSEDED)
            logdebug("Accepting a new goal")
            self.current_goal = self.next_goal
            self.new_goal = False
            self.preempt_request = self.new_goal_preempt_request
            self.new_goal_preempt_request = False
            self.current_goal.set_accepted(_ACCEPTED)
            return self.current_goal.get_goal()

    def is_new_goal_available(self) -> bool:
        return self.new_goal

    def is_preempt_requested(self) -> bool:
        return self.preempt_request

    def is_active(self) -> bool:
        if not self.current_goal.get_goal():
            return False
        return self.current_goal.get_goal_status().status in (GoalStatus.ACTIVE, GoalStatus.PREEMPTING)

    def get_default_result(self) -> Any:
        return self.action_server.ActionResultType()

    def set_succeeded(self, result: Any = None, text: str = "") -> None:
        with self.action_server.lock, self.lock:
            self.current_goal.set_succeeded(result if result is not None else self.get_default_result(), text)

    def set_aborted(self, result: Any = None, text: str = "") -> None:
        with self.action_server.lock, self.lock:
            self.current_goal.set_aborted(result if result is not None else self.get_default_result(), text)

    def set_preempted(self, result: Any = None, text: str = "") -> None:
        with self.action_server.lock, self.lock:
            logdebug("Setting the current goal as canceled")
            self.current_goal.set_canceled(result if result is not None else self.get_default_result(), text)

    def publish_feedback(self, feedback: Any) -> None:
        self.current_goal.publish_feedback(feedback)

    def register_goal_callback(self, cb: Callable[[], Any]) -> None:
        if self.execute_callback is not None:
            logwarn("Cannot call SimpleActionServer.register_goal_callback() because an executeCallback "
                          "exists. Not going to register it.")
        else:
            self.goal_callback = cb

    def register_preempt_callback(self, cb: Callable[[], Any]) -> None:
        self.preempt_callback = cb

    # ------------------------------------------------------------------ from the ActionServer

    def internal_goal_callback(self, goal: ServerGoalHandle) -> None:
        with self.execute_condition:
            logdebug("A new goal %s has been received by the single goal action server",
                           goal.get_goal_id().id)
            stamp = goal.get_goal_id().stamp
            newer_than_current = not self.current_goal.get_goal() or stamp >= self.current_goal.get_goal_id().stamp
            newer_than_next = not self.next_goal.get_goal() or stamp >= self.next_goal.get_goal_id().stamp
            if not (newer_than_current and newer_than_next):
                goal.set_canceled(None, _SUPERSEDED)
                return
            try:
                if self.next_goal.get_goal() and (not self.current_goal.get_goal()
                                                  or self.next_goal != self.current_goal):
                    self.next_goal.set_canceled(None, _SUPERSEDED)  # bumped before it ever ran
                self.next_goal = goal
                self.new_goal = True
                self.new_goal_preempt_request = False
                if self.is_active():
                    self.preempt_request = True
                    if self.preempt_callback is not None:
                        self.preempt_callback()
                if self.goal_callback is not None:
                    self.goal_callback()
            except Exception as exc:
                logerr("SimpleActionServer.internal_goal_callback - exception %s", str(exc))
            self.execute_condition.notify_all()

    def internal_preempt_callback(self, preempt: ServerGoalHandle) -> None:
        with self.lock:
            logdebug("A preempt has been received by the SimpleActionServer")
            if preempt == self.current_goal:
                self.preempt_request = True
                if self.preempt_callback is not None:
                    self.preempt_callback()
            elif preempt == self.next_goal:
                self.new_goal_preempt_request = True

    def executeLoop(self) -> None:
        while not core.is_shutdown():
            with self.execute_condition:
                if self.need_to_terminate:
                    return
                if not self.is_new_goal_available():
                    self.execute_condition.wait()  # woken by goals and by shutdown (_terminate)
                    continue
            if self.is_active():
                logerr("Should never reach this code with an active goal")
                return
            goal = self.accept_new_goal()
            if goal is None:
                continue
            assert self.execute_callback is not None
            try:
                self.execute_callback(goal)
                if self.is_active():
                    logwarn("Your executeCallback did not set the goal to a terminal status.  This is a bug "
                                  "in your ActionServer implementation. Fix your code!  For now, the ActionServer "
                                  "will set this goal to aborted")
                    self.set_aborted(None, "No terminal state was set.")
            except Exception as exc:
                if core.is_shutdown():
                    return
                logerr("Exception in your execute callback: %s\n%s", str(exc), traceback.format_exc())
                self.set_aborted(None, f"Exception in execute callback: {exc}")
