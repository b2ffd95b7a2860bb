"""A user's move_base client (rospy and actionlib, as the courses write them): asks move_base's
make_plan for the plan's length, sends one goal, and prints the final state and text and the
seconds of ROS time the goal took."""

import itertools
import math
import sys

import actionlib
import rospy
from geometry_msgs.msg import PoseStamped
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
from nav_msgs.srv import GetPlan

rospy.init_node("goal_client")
client = actionlib.SimpleActionClient("move_base", MoveBaseAction)
client.wait_for_server()
goal = MoveBaseGoal()
goal.target_pose.header.frame_id = "map"
goal.target_pose.pose.position.x, goal.target_pose.pose.position.y = float(sys.argv[1]), float(sys.argv[2])
goal.target_pose.pose.orientation.w = 1.0
rospy.wait_for_service("move_base/make_plan")
plan = rospy.ServiceProxy("move_base/make_plan", GetPlan)(PoseStamped(), goal.target_pose, 0.0).plan
points = [(p.pose.position.x, p.pose.position.y) for p in plan.poses]
print("plan", sum(math.dist(a, b) for a, b in itertools.pairwise(points)), flush=True)
start = rospy.get_time()
client.send_goal(goal)
client.wait_for_result()
print("state", client.get_state(), client.get_goal_status_text(), flush=True)
print("seconds", rospy.get_time() - start, flush=True)
