#!/usr/bin/env python
"""A rospy node reading the C++ package's own message."""
from cpp_msgs_demo.msg import Reading

import rospy


def got(reading: Reading) -> None:
    print(f"{reading.sensor} {reading.value:.1f} {list(reading.samples)}", flush=True)


rospy.init_node("reader")
rospy.Subscriber("readings", Reading, got)
print("ready", flush=True)
rospy.spin()
