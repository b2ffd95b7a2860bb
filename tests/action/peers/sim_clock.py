"""Publishes /clock fast: 0.1 s of ROS time every 10 ms of wall time, from t=1000 s."""

import time

import rospy
from rosgraph_msgs.msg import Clock

rospy.init_node("sim_clock")
pub = rospy.Publisher("/clock", Clock, queue_size=10)
ns = 1000 * 10**9
while not rospy.is_shutdown():
    pub.publish(Clock(clock=rospy.Time.from_nsec(ns)))
    ns += 100_000_000
    time.sleep(0.01)
