"""ActionServer: goals in on `<ns>/goal`, cancels on `<ns>/cancel`; status (latched), feedback
and result out. Goals are tracked as StatusTrackers and handed to the user as ServerGoalHandles.

Rules: nothing is done before start(); the status array goes out on every transition and at
actionlib_status_frequency Hz; a goal finished (or a cancel stub made) status_list_timeout
seconds ago leaves the list. Cancel matching is kame.action.CancelRequest.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray
from kame.action import CancelRequest, canceled_by_last_cancel
from kame.client import clock, core, process, timer, topics
from kame.client.action._log import logdebug, logwarn
from kame.client.action.exceptions import ActionException
from kame.client.action.server_goal_handle import ServerGoalHandle
from kame.client.action.status_tracker import StatusTracker

_EARLIER_CANCEL = ("This goal handle was canceled by the action server because its timestamp is before the "
                   "timestamp of the last cancel request")


def nop_cb(goal_handle: Any) -> None:
    pass


def action_types(ActionSpec: Any) -> tuple[Any, Any, Any, Any, Any]:
    """(ActionGoal, ActionResult, ActionFeedback, Goal, Result) of an action spec class."""
    try:
        spec = ActionSpec()
        return (type(spec.action_goal), type(spec.action_result), type(spec.action_feedback),
                type(spec.action_goal.goal), type(spec.action_result.result))
    except (AttributeError, TypeError):
        raise ActionException(f"Type is not an action spec: {ActionSpec}") from None


def queue_size_param(name: str, default: int) -> int:
    value = process.get_param(name, default)
    return value if isinstance(value, int) and value >= 0 else default


class ActionServer:
    def __init__(self, ns: str, ActionSpec: Any, goal_cb: Callable[[ServerGoalHandle], Any],
                 cancel_cb: Callable[[ServerGoalHandle], Any] = nop_cb, auto_start: bool = True) -> None:
        self.ns = ns
        self.ActionSpec = ActionSpec
        (self.ActionGoal, self.ActionResult, self.ActionFeedback, self.GoalType,
         self.ActionResultType) = action_types(ActionSpec)
        assert goal_cb is not None
        self.goal_callback = goal_cb
        self.cancel_callback = cancel_cb
        self.lock = threading.RLock()
        self.status_list: list[StatusTracker] = []
        self.last_cancel = clock.Time()
        self.status_list_timeout = clock.Duration(5)
        self.status_frequency = 5.0
        self.status_timer: timer.Timer | None = None
        self.goal_sub: topics.Subscriber | None = None
        self.cancel_sub: topics.Subscriber | None = None
        self.status_pub: topics.Publisher | None = None
        self.result_pub: topics.Publisher | None = None
        self.feedback_pub: topics.Publisher | None = None
        self.started = False
        self.auto_start = auto_start
        if auto_start:
            logwarn("You've passed in true for auto_start to the python action server, you should always "
                          "pass in false to avoid race conditions.")
            self.start()

    def register_goal_callback(self, cb: Callable[[ServerGoalHandle], Any]) -> None:
        self.goal_callback = cb

    def register_cancel_callback(self, cancel_cb: Callable[[ServerGoalHandle], Any]) -> None:
        self.cancel_callback = cancel_cb

    def start(self) -> None:
        with self.lock:
            self.initialize()
            self.started = True
            self.publish_status()

    def stop(self) -> None:
        with self.lock:
            self.started = False
            if self.status_timer is not None:
                self.status_timer.shutdown()
            for topic in (self.goal_sub, self.cancel_sub, self.status_pub, self.feedback_pub, self.result_pub):
                if topic is not None:
                    topic.unregister()

    def initialize(self) -> None:
        base = core.remap_name(self.ns)
        pub_queue = queue_size_param("actionlib_server_pub_queue_size", 50)
        self.status_pub = topics.Publisher(base + "/status", GoalStatusArray, latch=True, queue_size=pub_queue)
        self.result_pub = topics.Publisher(base + "/result", self.ActionResult, queue_size=pub_queue)
        self.feedback_pub = topics.Publisher(base + "/feedback", self.ActionFeedback, queue_size=pub_queue)
        sub_queue: int | None = queue_size_param("actionlib_server_sub_queue_size", -1)
        if sub_queue is not None and sub_queue <= 0:
            sub_queue = None
        self.goal_sub = topics.Subscriber(base + "/goal", self.ActionGoal, callback=self.internal_goal_callback,
                                         queue_size=sub_queue)
        self.cancel_sub = topics.Subscriber(base + "/cancel", GoalID, callback=self.internal_cancel_callback,
                                           queue_size=sub_queue)
        deprecated = base + "/status_frequency"
        if process.has_param(deprecated):
            self.status_frequency = float(process.get_param(deprecated, 5.0))
            logwarn("You're using the deprecated status_frequency parameter, please switch to "
                          "actionlib_status_frequency.")
        else:
            found = process.search_param("actionlib_status_frequency")
            self.status_frequency = 5.0 if found is None else float(process.get_param(found, 5.0))
        self.status_list_timeout = clock.Duration.from_sec(float(process.get_param(base + "/status_list_timeout",
                                                                                 5.0)))
        if self.status_frequency > 0.0:
            self.status_timer = timer.Timer(clock.Duration.from_sec(1.0 / self.status_frequency),
                                            self.publish_status_async)

    # ------------------------------------------------------------------ out

    def publish_result(self, status: GoalStatus, result: Any) -> None:
        with self.lock:
            msg = self.ActionResult()
            msg.header.stamp = clock.Time.now()
            msg.status = status
            msg.result = result
            if not core.is_shutdown() and self.result_pub is not None:
                self.result_pub.publish(msg)
            self.publish_status()

    def publish_feedback(self, status: GoalStatus, feedback: Any) -> None:
        with self.lock:
            msg = self.ActionFeedback()
            msg.header.stamp = clock.Time.now()
            msg.status = status
            msg.feedback = feedback
            if not core.is_shutdown() and self.feedback_pub is not None:
                self.feedback_pub.publish(msg)

    def publish_status_async(self, event: Any = None) -> None:
        with self.lock:
            if self.started:
                self.publish_status()

    def publish_status(self) -> None:
        with self.lock:
            now = clock.Time.now()
            kept = [st for st in self.status_list
                    if st.handle_destruction_time.is_zero()
                    or st.handle_destruction_time + self.status_list_timeout >= now]
            self.status_list = kept
            array = GoalStatusArray(status_list=[st.status for st in kept])
            array.header.stamp = now
            if not core.is_shutdown() and self.status_pub is not None:
                self.status_pub.publish(array)

    # ------------------------------------------------------------------ in

    def internal_cancel_callback(self, goal_id: GoalID) -> None:
        with self.lock:
            if not self.started:
                return
            logdebug("The action server has received a new cancel request")
            request = CancelRequest(goal_id.id, goal_id.stamp.to_nsec())
            for st in list(self.status_list):
                if not request.matches(st.status.goal_id.id, st.status.goal_id.stamp.to_nsec()):
                    continue
                if st.handle_tracker is None:
                    st.handle_tracker = True
                    st.handle_destruction_time = clock.Time.now()
                handle = ServerGoalHandle(st, self, st.handle_tracker)
                if handle.set_cancel_requested():
                    self.cancel_callback(handle)
            if request.remembers_unknown_id({st.status.goal_id.id for st in self.status_list}):
                stub = StatusTracker(GoalID(stamp=goal_id.stamp, id=goal_id.id), GoalStatus.RECALLING)
                stub.handle_destruction_time = clock.Time.now()
                self.status_list.append(stub)
            if goal_id.stamp > self.last_cancel:
                self.last_cancel = goal_id.stamp

    def internal_goal_callback(self, goal: Any) -> None:
        with self.lock:
            if not self.started:
                return
            logdebug("The action server has received a new goal request")
            for st in self.status_list:
                if st.status.goal_id.id != goal.goal_id.id:
                    continue
                logdebug("Goal %s was already in the status list with status %i",
                               goal.goal_id.id, st.status.status)
                if st.status.status == GoalStatus.RECALLING:  # its cancel came first
                    st.status.status = GoalStatus.RECALLED
                    self.publish_result(st.status, self.ActionResultType())
                if st.handle_tracker is None:
                    st.handle_destruction_time = clock.Time.now()
                return
            st = StatusTracker(goal=goal)
            st.handle_tracker = True
            self.status_list.append(st)
            handle = ServerGoalHandle(st, self, st.handle_tracker)
            if canceled_by_last_cancel(goal.goal_id.stamp.to_nsec(), self.last_cancel.to_nsec()):
                handle.set_canceled(None, _EARLIER_CANCEL)
            else:
                self.goal_callback(handle)
