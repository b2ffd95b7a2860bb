"""A real rospy node (Debian's /usr/bin/python3) that drives kame's turtlesim and reads its pose.

Debian has no turtlesim Python module: the node publishes geometry_msgs/Twist (Debian has it)
and reads turtlesim/Pose as rospy.AnyMsg, building the class from the connection header's
message_definition with genpy.dynamic. Prints `start x y` and `end x y theta`.
"""

import sys
import time

import genpy.dynamic
import rospy
from geometry_msgs.msg import Twist

poses = []
classes = {}


def on_pose(raw):
    header = raw._connection_header
    kind = header["type"]
    if kind not in classes:
        classes[kind] = genpy.dynamic.generate_dynamic(kind, header["message_definition"])[kind]
    poses.append(classes[kind]().deserialize(raw._buff))


rospy.init_node("debian_driver")
rospy.Subscriber("/turtle1/pose", rospy.AnyMsg, on_pose)
pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
deadline = time.time() + 10
while (not poses or pub.get_num_connections() == 0) and time.time() < deadline:
    time.sleep(0.05)
if not poses:
    sys.exit("no pose")
start = poses[-1]
print(f"start {start.x:.6f} {start.y:.6f}", flush=True)
twist = Twist()
twist.linear.x = 1.0
twist.angular.z = 0.5
for _ in range(5):  # half a second of commands, then the 1 s timeout
    pub.publish(twist)
    time.sleep(0.1)
time.sleep(1.6)
end = poses[-1]
print(f"end {end.x:.6f} {end.y:.6f} {end.theta:.6f} {end._type}", flush=True)
