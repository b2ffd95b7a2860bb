"""tf2_ros.BufferServer: answers tf2_msgs/LookupTransform goals from a Buffer (what tf2_ros's
buffer_server program runs). A goal waits, woken by arriving transforms, up to its timeout,
then is answered with the transform or tf2's error code and text (always SUCCEEDED, as
tf2_ros's server does). Each waiting goal has a thread the server owns and joins in stop()."""

import threading

from actionlib import ActionServer
from kame.tf.errors import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from tf2_msgs.msg import LookupTransformAction, LookupTransformResult, TF2Error

CODES = ((LookupException, TF2Error.LOOKUP_ERROR), (ConnectivityException, TF2Error.CONNECTIVITY_ERROR),
         (ExtrapolationException, TF2Error.EXTRAPOLATION_ERROR),
         (InvalidArgumentException, TF2Error.INVALID_ARGUMENT_ERROR), (TimeoutException, TF2Error.TIMEOUT_ERROR))


class BufferServer:
    def __init__(self, buffer, ns, auto_start=True):
        self.buffer = buffer
        self._lock = threading.Lock()
        self._waiters = set()
        self._stopped = threading.Event()
        self.server = ActionServer(ns, LookupTransformAction, self._on_goal, auto_start=False)
        if auto_start:
            self.start()

    def start(self):
        self.server.start()

    def stop(self):
        self._stopped.set()
        self.buffer.wake()
        with self._lock:
            waiters = list(self._waiters)
        for thread in waiters:
            thread.join()

    def _on_goal(self, handle):
        handle.set_accepted()
        thread = threading.Thread(target=self._answer, args=(handle,), name="tf2-buffer-server-goal", daemon=True)
        with self._lock:
            self._waiters.add(thread)
        thread.start()

    def _answer(self, handle):
        try:
            goal = handle.get_goal()
            result = LookupTransformResult()
            fixed = goal.fixed_frame if goal.advanced else ""
            self.buffer.wait_for(goal.target_frame, goal.source_frame, goal.source_time, goal.timeout, self._stopped,
                                 goal.target_time, fixed)
            try:
                if goal.advanced:
                    result.transform = self.buffer.lookup_transform_full(
                        goal.target_frame, goal.target_time, goal.source_frame, goal.source_time, goal.fixed_frame)
                else:
                    result.transform = self.buffer.lookup_transform(goal.target_frame, goal.source_frame,
                                                                    goal.source_time)
            except TransformException as exc:
                result.error.error = next((code for kind, code in CODES if isinstance(exc, kind)),
                                          TF2Error.TRANSFORM_ERROR)
                result.error.error_string = str(exc)
            if not self._stopped.is_set():
                handle.set_succeeded(result)
        finally:
            with self._lock:
                self._waiters.discard(threading.current_thread())
