"""ActionClient: goals out on `<ns>/goal`, cancels on `<ns>/cancel`; status, feedback and result in.

Each sent goal has a CommStateMachine (kame.action.comm_state) fed by the status arrays and
results for its id; the user holds it through a ClientGoalHandle (the client keeps only weak
references: a goal whose handles are gone is forgotten). When the server whose status we
follow loses its connection for good, its goals are judged on an empty status array (LOST).
"""

from __future__ import annotations

import itertools
import threading
import weakref
from collections.abc import Callable
from typing import Any

from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray
from kame import action as _rules
from kame.action import CommState as _Comm
from kame.action import InvalidTransition, comm_steps, lost_when_unlisted
from kame.client import clock, core, timer, topics
from kame.client.action._log import logdebug, logerr, logwarn
from kame.client.action.action_server import action_types, queue_size_param
from kame.client.action.exceptions import ActionException
from std_msgs.msg import Header

__all__ = ["ActionClient", "ActionException", "ClientGoalHandle", "CommState", "CommStateMachine", "GoalID",
           "GoalStatus", "GoalStatusArray", "TerminalState", "get_name_of_constant"]


def get_name_of_constant(C: Any, n: int) -> str:
    for k, v in C.__dict__.items():
        if isinstance(v, int) and v == n:
            return str(k)
    return f"NO_SUCH_STATE_{n}"


class CommState:
    WAITING_FOR_GOAL_ACK = int(_Comm.WAITING_FOR_GOAL_ACK)
    PENDING = int(_Comm.PENDING)
    ACTIVE = int(_Comm.ACTIVE)
    WAITING_FOR_RESULT = int(_Comm.WAITING_FOR_RESULT)
    WAITING_FOR_CANCEL_ACK = int(_Comm.WAITING_FOR_CANCEL_ACK)
    RECALLING = int(_Comm.RECALLING)
    PREEMPTING = int(_Comm.PREEMPTING)
    DONE = int(_Comm.DONE)
    LOST = int(_Comm.LOST)

    @classmethod
    def to_string(cls, n: int) -> str:
        return get_name_of_constant(cls, n)


class TerminalState:
    RECALLED = GoalStatus.RECALLED
    REJECTED = GoalStatus.REJECTED
    PREEMPTED = GoalStatus.PREEMPTED
    ABORTED = GoalStatus.ABORTED
    SUCCEEDED = GoalStatus.SUCCEEDED
    LOST = GoalStatus.LOST

    @classmethod
    def to_string(cls, n: int) -> str:
        return get_name_of_constant(cls, n)


if not hasattr(GoalStatus, "to_string"):  # as actionlib does to the message class
    GoalStatus.to_string = classmethod(get_name_of_constant)

_TERMINAL_OR_LOST = (GoalStatus.PREEMPTED, GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.REJECTED,
                     GoalStatus.RECALLED, GoalStatus.LOST)


class CommStateMachine:
    def __init__(self, action_goal: Any, transition_cb: Callable[[ClientGoalHandle], Any] | None,
                 feedback_cb: Callable[[ClientGoalHandle, Any], Any] | None,
                 send_goal_fn: Callable[[Any], Any], send_cancel_fn: Callable[[GoalID], Any]) -> None:
        self.action_goal = action_goal
        self.transition_cb = transition_cb
        self.feedback_cb = feedback_cb
        self.send_goal_fn = send_goal_fn
        self.send_cancel_fn = send_cancel_fn
        self.state = CommState.WAITING_FOR_GOAL_ACK
        self.mutex = threading.RLock()
        self.latest_goal_status = GoalStatus(status=GoalStatus.PENDING)
        self.latest_result: Any = None

    def __eq__(self, o: object) -> bool:
        return isinstance(o, CommStateMachine) and self.action_goal.goal_id.id == o.action_goal.goal_id.id

    def __hash__(self) -> int:
        return hash(self.action_goal.goal_id.id)

    def set_state(self, state: int) -> None:
        self.state = state

    def update_status(self, status_array: GoalStatusArray) -> None:
        with self.mutex:
            if self.state == CommState.DONE:
                return
            goal_id = self.action_goal.goal_id.id
            status = next((s for s in status_array.status_list if s.goal_id.id == goal_id), None)
            if status is None:
                if lost_when_unlisted(_Comm(self.state)):
                    self._mark_as_lost()
                return
            self.latest_goal_status = status
            try:
                steps = comm_steps(_Comm(self.state), status.status)
            except InvalidTransition as exc:
                logerr(str(exc))
                return
            except ValueError:
                logerr("Got an unknown status from the ActionServer: %i", status.status)
                return
            for step in steps:
                self.transition_to(int(step))

    def transition_to(self, state: int) -> None:
        logdebug("Transitioning to %s (from %s, goal: %s)", CommState.to_string(state),
                       CommState.to_string(self.state), self.action_goal.goal_id.id)
        self.state = state
        if self.transition_cb is not None:
            self.transition_cb(ClientGoalHandle(self))

    def _mark_as_lost(self) -> None:
        self.latest_goal_status = GoalStatus(goal_id=self.latest_goal_status.goal_id, status=GoalStatus.LOST,
                                             text=self.latest_goal_status.text)
        self.transition_to(CommState.DONE)

    def update_result(self, action_result: Any) -> None:
        if action_result.status.goal_id.id != self.action_goal.goal_id.id:
            return
        with self.mutex:
            if self.state == CommState.DONE:
                if self.latest_goal_status.status != GoalStatus.LOST:
                    logerr("Got a result when we were already in the DONE state")
                return
            self.latest_goal_status = action_result.status
            self.latest_result = action_result
            self.update_status(GoalStatusArray(status_list=[action_result.status]))
            if self.state != CommState.DONE:
                self.transition_to(CommState.DONE)

    def update_feedback(self, action_feedback: Any) -> None:
        if action_feedback.status.goal_id.id != self.action_goal.goal_id.id:
            return
        if self.feedback_cb is not None and self.state != CommState.DONE:
            self.feedback_cb(ClientGoalHandle(self), action_feedback.feedback)


class ClientGoalHandle:
    def __init__(self, comm_state_machine: CommStateMachine) -> None:
        self.comm_state_machine = comm_state_machine

    def __eq__(self, o: object) -> bool:
        return isinstance(o, ClientGoalHandle) and self.comm_state_machine == o.comm_state_machine

    def __ne__(self, o: object) -> bool:
        return not self == o

    def __hash__(self) -> int:
        return hash(self.comm_state_machine)

    def cancel(self) -> None:
        csm = self.comm_state_machine
        with csm.mutex:
            csm.send_cancel_fn(GoalID(stamp=clock.Time(0), id=csm.action_goal.goal_id.id))
            csm.transition_to(CommState.WAITING_FOR_CANCEL_ACK)

    def get_comm_state(self) -> int:
        return self.comm_state_machine.state

    def get_goal_status(self) -> int:
        return int(self.comm_state_machine.latest_goal_status.status)

    def get_goal_status_text(self) -> str:
        return str(self.comm_state_machine.latest_goal_status.text)

    def get_goal_id(self) -> GoalID:
        return self.comm_state_machine.action_goal.goal_id

    def get_result(self) -> Any:
        latest = self.comm_state_machine.latest_result
        return latest.result if latest is not None else None

    def get_terminal_state(self) -> int:
        csm = self.comm_state_machine
        with csm.mutex:
            if csm.state != CommState.DONE:
                logwarn("Asking for the terminal state when we're in [%s]", CommState.to_string(csm.state))
            status = int(csm.latest_goal_status.status)
            if status in _TERMINAL_OR_LOST:
                return status
            logerr("Asking for a terminal state, but the goal status is %d", status)
            return int(GoalStatus.LOST)


_goal_counter = itertools.count(1)


class GoalManager:
    """The goals of one ActionClient, held weakly."""

    def __init__(self, ActionSpec: Any) -> None:
        self.ActionSpec = ActionSpec
        self.ActionGoal, self.ActionResult, self.ActionFeedback, _, _ = action_types(ActionSpec)
        self.list_mutex = threading.RLock()
        self.statuses: list[weakref.ref[CommStateMachine]] = []
        self.send_goal_fn: Callable[[Any], Any] = lambda goal: None
        self.cancel_fn: Callable[[GoalID], Any] = lambda goal_id: None

    def _generate_id(self) -> GoalID:
        now = clock.Time.now()
        return GoalID(id=_rules.client_goal_id(core.get_caller_id(), next(_goal_counter), now.secs, now.nsecs),
                      stamp=now)

    def register_send_goal_fn(self, fn: Callable[[Any], Any]) -> None:
        self.send_goal_fn = fn

    def register_cancel_fn(self, fn: Callable[[GoalID], Any]) -> None:
        self.cancel_fn = fn

    def init_goal(self, goal: Any, transition_cb: Callable[[ClientGoalHandle], Any] | None = None,
                  feedback_cb: Callable[[ClientGoalHandle, Any], Any] | None = None) -> ClientGoalHandle:
        action_goal = self.ActionGoal(header=Header(), goal_id=self._generate_id(), goal=goal)
        action_goal.header.stamp = clock.get_rostime()
        csm = CommStateMachine(action_goal, transition_cb, feedback_cb, self.send_goal_fn, self.cancel_fn)
        with self.list_mutex:
            self.statuses.append(weakref.ref(csm))
        self.send_goal_fn(action_goal)
        return ClientGoalHandle(csm)

    def _live(self) -> list[CommStateMachine]:
        with self.list_mutex:
            live = [csm for csm in (ref() for ref in self.statuses) if csm is not None]
            self.statuses = [weakref.ref(csm) for csm in live]
            return live

    def update_statuses(self, status_array: GoalStatusArray) -> None:
        for csm in self._live():
            csm.update_status(status_array)

    def update_results(self, action_result: Any) -> None:
        for csm in self._live():
            csm.update_result(action_result)

    def update_feedbacks(self, action_feedback: Any) -> None:
        for csm in self._live():
            csm.update_feedback(action_feedback)


class ActionClient:
    WATCH_PERIOD = 0.5  # how often a followed server's status connection is checked

    def __init__(self, ns: str, ActionSpec: Any) -> None:
        self.ns = ns
        self.ActionSpec = ActionSpec
        self.ActionGoal, self.ActionResult, self.ActionFeedback, _, _ = action_types(ActionSpec)
        self.last_status_msg: GoalStatusArray | None = None
        self._wakers: set[threading.Event] = set()  # of the wait_for_server calls under way
        self._wakers_lock = threading.Lock()
        self._watch: timer.Timer | None = None
        self._server_missing = 0
        base = core.remap_name(ns)
        queue = queue_size_param("actionlib_client_pub_queue_size", 10)
        self.pub_queue_size = queue
        self.pub_goal = topics.Publisher(base + "/goal", self.ActionGoal, queue_size=queue)
        self.pub_cancel = topics.Publisher(base + "/cancel", GoalID, queue_size=queue)
        self.manager = GoalManager(ActionSpec)
        self.manager.register_send_goal_fn(self.pub_goal.publish)
        self.manager.register_cancel_fn(self.pub_cancel.publish)
        sub_queue: int | None = queue_size_param("actionlib_client_sub_queue_size", -1)
        if sub_queue is not None and sub_queue <= 0:
            sub_queue = None
        self.status_sub = topics.Subscriber(base + "/status", GoalStatusArray, callback=self._status_cb,
                                           queue_size=sub_queue)
        self.result_sub = topics.Subscriber(base + "/result", self.ActionResult, callback=self._result_cb,
                                           queue_size=sub_queue)
        self.feedback_sub = topics.Subscriber(base + "/feedback", self.ActionFeedback, callback=self._feedback_cb,
                                             queue_size=sub_queue)

    def stop(self) -> None:
        if self._watch is not None:
            self._watch.shutdown()
        for topic in (self.pub_goal, self.pub_cancel, self.status_sub, self.result_sub, self.feedback_sub):
            topic.unregister()

    def send_goal(self, goal: Any, transition_cb: Callable[[ClientGoalHandle], Any] | None = None,
                  feedback_cb: Callable[[ClientGoalHandle, Any], Any] | None = None) -> ClientGoalHandle:
        return self.manager.init_goal(goal, transition_cb, feedback_cb)

    def cancel_all_goals(self) -> None:
        self.pub_cancel.publish(GoalID(stamp=clock.Time(0), id=""))

    def cancel_goals_at_and_before_time(self, time: Any) -> None:
        self.pub_cancel.publish(GoalID(stamp=time, id=""))

    def wait_for_action_server_to_start(self, timeout: Any = None) -> bool:
        return self.wait_for_server(timeout)

    # ------------------------------------------------------------------ readiness

    def _server_id(self) -> str | None:
        msg = self.last_status_msg
        header = getattr(msg, "_connection_header", None) if msg is not None else None
        return header.get("callerid") if header else None

    def _server_ready(self) -> bool:
        """The status came from a node that subscribes to our goal and cancel and publishes
        the result and feedback we subscribe to."""
        server = self._server_id()
        if server is None:
            return False
        return (_publishes_to(self.pub_goal, server) and _publishes_to(self.pub_cancel, server)
                and _subscribed_from(self.result_sub, server) and _subscribed_from(self.feedback_sub, server))

    def wait_for_server(self, timeout: Any = None) -> bool:
        """Block until the server is connected; a zero (or no) timeout waits for ever.

        One wait on an event that everything the answer depends on sets: a status message, a
        connection made on one of the four other topics, shutdown, and (for a deadline on
        simulated time) each /clock tick. The event is cleared before looking, so nothing that
        happens while we look is missed."""
        seconds = 0.0 if timeout is None else (timeout.to_sec() if hasattr(timeout, "to_sec") else float(timeout))
        deadline = clock.get_rostime() + clock.Duration.from_sec(seconds)
        woken = threading.Event()

        def wake(link: Any = None) -> None:
            woken.set()

        connecting = [t.impl for t in (self.pub_goal, self.pub_cancel, self.result_sub, self.feedback_sub)
                      if t.impl is not None]
        for impl in connecting:
            impl.add_connect_callback(wake)
        with self._wakers_lock:
            self._wakers.add(woken)
        try:
            with core.woken_at_shutdown(woken), clock.woken_at_change(woken):
                while not core.is_shutdown():
                    woken.clear()
                    if self._server_ready():
                        return True
                    left = (deadline - clock.get_rostime()).to_sec()
                    if seconds > 0 and left <= 0:
                        return False
                    # on simulated time the deadline comes with a /clock tick, which wakes us
                    woken.wait(left if seconds > 0 and not clock.is_sim_time() else None)
        finally:
            with self._wakers_lock:
                self._wakers.discard(woken)
            for impl in connecting:
                impl.remove_connect_callback(wake)
        return False

    # ------------------------------------------------------------------ in

    def _status_cb(self, msg: GoalStatusArray) -> None:
        self.last_status_msg = msg
        self._server_missing = 0
        with self._wakers_lock:
            for waker in self._wakers:
                waker.set()
        if self._watch is None:
            self._watch = timer.Timer(clock.Duration.from_sec(self.WATCH_PERIOD), self._check_server)
        self.manager.update_statuses(msg)

    def _result_cb(self, msg: Any) -> None:
        self.manager.update_results(msg)

    def _feedback_cb(self, msg: Any) -> None:
        self.manager.update_feedbacks(msg)

    def _check_server(self, event: Any = None) -> None:
        """A server whose status link stays down for two checks is gone: judge its goals on an
        empty status array (the ones it was running become LOST). Warned once per loss."""
        impl = self.status_sub.impl
        if impl is None or self._server_missing > 2:
            return
        if any(link.connected for link in impl.links.values()):
            self._server_missing = 0
            return
        self._server_missing += 1
        if self._server_missing == 2:
            self._server_missing = 3
            live = [csm for csm in self.manager._live() if csm.state != CommState.DONE]
            if live:
                logwarn("The action server %s of [%s] went away while %d goal(s) were pending",
                              self._server_id() or "?", core.resolve_name(self.ns), len(live))
            self.manager.update_statuses(GoalStatusArray())


def _publishes_to(pub: topics.Publisher, node: str) -> bool:
    impl = pub.impl
    return impl is not None and any(link.callerid == node for link in impl.links)


def _subscribed_from(sub: topics.Subscriber, node: str) -> bool:
    impl = sub.impl
    return impl is not None and any(link.connected and link.callerid == node for link in impl.links.values())
