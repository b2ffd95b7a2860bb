#!/usr/bin/env python3
# mypy: ignore-errors
# The Averaging tutorial's number source: normally distributed samples (mean 5, sd 1) on random_number.
import random

import rospy
from std_msgs.msg import Float32


def gen_number():
    pub = rospy.Publisher('random_number', Float32, queue_size=10)
    rospy.init_node('random_number_generator', log_level=rospy.INFO)
    rospy.loginfo("Generating random numbers")
    while not rospy.is_shutdown():
        pub.publish(Float32(random.normalvariate(5, 1)))
        rospy.sleep(0.05)


if __name__ == '__main__':
    try:
        gen_number()
    except rospy.ROSInterruptException:
        pass
