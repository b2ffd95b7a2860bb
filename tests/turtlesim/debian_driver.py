"""A real rospy node (Debian's /usr/bin/python3) that drives kame's turtlesim and reads its pose.

Debian has no turtlesim Python module: the node publishes geometry_msgs/Twist (Debian has it)
and reads turtlesim/Pose as rospy.AnyMsg, building the class from the connection header's
message_definition with genpy.dynamic. Prints `start x y` and `end x y theta type span`
(span: the seconds from the first command sent to the last).
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
sent = []
for _ in range(5):  # half a second of commands, then the 1 s timeout
    pub.publish(twist)
    sent.append(time.monotonic())
    time.sleep(0.1)
# until the turtle has moved and stopped again (its 1 s timeout after the last command), not a
# fixed time: a loaded machine delays the commands and the poses
deadline = time.monotonic() + 15
while not (any(p.linear_velocity for p in poses) and poses[-1].linear_velocity == 0.0
           and poses[-1].angular_velocity == 0.0):
    if time.monotonic() > deadline:
        sys.exit("the turtle did not move and stop")
    time.sleep(0.05)
end = poses[-1]
# how long the commands took to send: 0.4 s, or more when this process was held up
print(f"end {end.x:.6f} {end.y:.6f} {end.theta:.6f} {end._type} {sent[-1] - sent[0]:.3f}", flush=True)
