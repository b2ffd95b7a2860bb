"""A user's move_base client (rospy and actionlib, as the courses write them): sends one goal
and prints the final state and text."""

import sys

import actionlib
import rospy
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal

rospy.init_node("goal_client")
client = actionlib.SimpleActionClient("move_base", MoveBaseAction)
client.wait_for_server()
goal = MoveBaseGoal()
goal.target_pose.header.frame_id = "map"
goal.target_pose.pose.position.x, goal.target_pose.pose.position.y = float(sys.argv[1]), float(sys.argv[2])
goal.target_pose.pose.orientation.w = 1.0
client.send_goal(goal)
client.wait_for_result()
print("state", client.get_state(), client.get_goal_status_text(), flush=True)
