"""tf2_ros.BufferClient: lookups answered by a BufferServer over the tf2_msgs/LookupTransform
action, with tf2's exceptions rebuilt from the result's error code."""

import rospy
from actionlib import SimpleActionClient
from actionlib_msgs.msg import GoalStatus
from kame.tf.errors import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from tf2_msgs.msg import LookupTransformAction, LookupTransformGoal, TF2Error

from .buffer_interface import NO_WAIT, BufferInterface

ERRORS = {TF2Error.LOOKUP_ERROR: LookupException, TF2Error.CONNECTIVITY_ERROR: ConnectivityException,
          TF2Error.EXTRAPOLATION_ERROR: ExtrapolationException,
          TF2Error.INVALID_ARGUMENT_ERROR: InvalidArgumentException, TF2Error.TIMEOUT_ERROR: TimeoutException}


class BufferClient(BufferInterface):
    def __init__(self, ns, check_frequency=None, timeout_padding=None):
        BufferInterface.__init__(self)
        self.client = SimpleActionClient(ns, LookupTransformAction)
        self.timeout_padding = timeout_padding if timeout_padding is not None else rospy.Duration.from_sec(2.0)
        if check_frequency is not None:
            rospy.logwarn("Argument check_frequency is deprecated and should not be used.")

    def wait_for_server(self, timeout=None):
        return self.client.wait_for_server(timeout if timeout is not None else rospy.Duration())

    def lookup_transform(self, target_frame, source_frame, time, timeout=NO_WAIT):
        goal = LookupTransformGoal(target_frame=target_frame, source_frame=source_frame, source_time=time,
                                   timeout=timeout, advanced=False)
        return self._process_goal(goal)

    def lookup_transform_full(self, target_frame, target_time, source_frame, source_time, fixed_frame,
                              timeout=NO_WAIT):
        goal = LookupTransformGoal(target_frame=target_frame, source_frame=source_frame, source_time=source_time,
                                   timeout=timeout, target_time=target_time, fixed_frame=fixed_frame, advanced=True)
        return self._process_goal(goal)

    def can_transform(self, target_frame, source_frame, time, timeout=NO_WAIT):
        try:
            self.lookup_transform(target_frame, source_frame, time, timeout)
            return True
        except TransformException:
            return False

    def can_transform_full(self, target_frame, target_time, source_frame, source_time, fixed_frame, timeout=NO_WAIT):
        try:
            self.lookup_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
            return True
        except TransformException:
            return False

    def _process_goal(self, goal):
        self.client.send_goal(goal)
        if not self.client.wait_for_result(goal.timeout + self.timeout_padding):
            raise TimeoutException("The LookupTransform goal sent to the BufferServer did not come back in the "
                                   "specified time. Something is likely wrong with the server")
        if self.client.get_state() != GoalStatus.SUCCEEDED:
            raise TimeoutException("The LookupTransform goal sent to the BufferServer did not come back with "
                                   "SUCCEEDED status. Something is likely wrong with the server.")
        result = self.client.get_result()
        if result is None or result.error is None:
            raise TransformException("The BufferServer returned None for result or result.error!  Something is "
                                     "likely wrong with the server.")
        if result.error.error != TF2Error.NO_ERROR:
            raise ERRORS.get(result.error.error, TransformException)(result.error.error_string)
        return result.transform
