"""Publishes /clock fast: 0.1 s of ROS time (or the first argument's seconds) every 10 ms of wall
time, from t=1 s.

It starts near zero on purpose: a client whose /clock subscription connects after it computed
a deadline (rospy time is 0 until the first /clock, in real rospy too) then has that deadline
in the near future, not 1000 s in the past."""

import sys
import time

import rospy
from rosgraph_msgs.msg import Clock

rospy.init_node("sim_clock")
pub = rospy.Publisher("/clock", Clock, queue_size=10)
step_ns = round(float(sys.argv[1]) * 1e9) if len(sys.argv) > 1 else 100_000_000
ns = 1 * 10**9
while not rospy.is_shutdown():
    pub.publish(Clock(clock=rospy.Time.from_nsec(ns)))
    ns += step_ns
    time.sleep(0.01)
