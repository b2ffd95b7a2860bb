#!/usr/bin/env python3
# ruff: noqa
# mypy: ignore-errors
# (the tutorial text as users copy it, so the linters leave it alone)
# The rospy tutorial listener, as the ROS wiki gives it.
# (ros_tutorials installs it as both `listener` and `listener.py`; tutorials use either name.)
import rospy
from std_msgs.msg import String

def callback(data):
    rospy.loginfo(rospy.get_caller_id() + "I heard %s", data.data)

def listener():
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber("chatter", String, callback)
    rospy.spin()

if __name__ == '__main__':
    listener()
