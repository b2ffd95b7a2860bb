#!/usr/bin/env python3
# mypy: ignore-errors
# ruff: noqa: UP031  (the tutorial formats with %)
# The actionlib tutorial's Fibonacci server (SimpleActionServer with an execute callback),
# written the way the ROS wiki teaches it; the action is served under the node's name.
import actionlib
import actionlib_tutorials.msg
import rospy


class FibonacciAction:
    _feedback = actionlib_tutorials.msg.FibonacciFeedback()
    _result = actionlib_tutorials.msg.FibonacciResult()

    def __init__(self, name):
        self._action_name = name
        self._as = actionlib.SimpleActionServer(self._action_name, actionlib_tutorials.msg.FibonacciAction,
                                                execute_cb=self.execute_cb, auto_start=False)
        self._as.start()

    def execute_cb(self, goal):
        r = rospy.Rate(1)
        success = True
        self._feedback.sequence = [0, 1]
        rospy.loginfo('%s: Executing, creating fibonacci sequence of order %i with seeds %i, %i'
                      % (self._action_name, goal.order, self._feedback.sequence[0], self._feedback.sequence[1]))
        for i in range(1, goal.order):
            if self._as.is_preempt_requested():
                rospy.loginfo(f'{self._action_name}: Preempted')
                self._as.set_preempted()
                success = False
                break
            self._feedback.sequence.append(self._feedback.sequence[i] + self._feedback.sequence[i - 1])
            self._as.publish_feedback(self._feedback)
            r.sleep()
        if success:
            self._result.sequence = self._feedback.sequence
            rospy.loginfo(f'{self._action_name}: Succeeded')
            self._as.set_succeeded(self._result)


if __name__ == '__main__':
    rospy.init_node('fibonacci')
    server = FibonacciAction(rospy.get_name())
    rospy.spin()
