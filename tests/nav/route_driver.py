"""A user's scripted drive (rospy, as the courses write them): publishes cmd_vel legs given as
`linear,angular,seconds` arguments, each timed in ROS time (the simulator's clock, whatever its
real-time factor), then stops the robot and prints "done"."""

import sys

import rospy
from geometry_msgs.msg import Twist

rospy.init_node("route_driver")
cmd_vel = rospy.Publisher("cmd_vel", Twist, queue_size=1)
rate = rospy.Rate(20)
while cmd_vel.get_num_connections() == 0 or rospy.get_time() == 0.0:  # the simulator listens, its clock runs
    rate.sleep()
for leg in sys.argv[1:]:
    linear, angular, seconds = (float(v) for v in leg.split(","))
    twist = Twist()
    twist.linear.x, twist.angular.z = linear, angular
    end = rospy.get_time() + seconds
    while rospy.get_time() < end:
        cmd_vel.publish(twist)
        rate.sleep()
cmd_vel.publish(Twist())
print("done", flush=True)
