#!/usr/bin/env python3
# mypy: ignore-errors
# The actionlib tutorial's Fibonacci client: wait for the server, send order 20, print the result.
import sys

import actionlib
import actionlib_tutorials.msg
import rospy


def fibonacci_client():
    client = actionlib.SimpleActionClient('fibonacci', actionlib_tutorials.msg.FibonacciAction)
    client.wait_for_server()
    goal = actionlib_tutorials.msg.FibonacciGoal(order=20)
    client.send_goal(goal)
    client.wait_for_result()
    return client.get_result()


if __name__ == '__main__':
    try:
        rospy.init_node('fibonacci_client_py')
        result = fibonacci_client()
        print("Result:", ', '.join([str(n) for n in result.sequence]))
    except rospy.ROSInterruptException:
        print("program interrupted before completion", file=sys.stderr)
