#!/usr/bin/env python3
# A course exercise as students write it: the package's data file found with rospkg, two
# stamped sensors paired by message_filters, the gain tuned live with dynamic_reconfigure.
import os

from course_fusion.cfg import FusionConfig

import message_filters
import rospkg
import rospy
from dynamic_reconfigure.server import Server
from geometry_msgs.msg import PointStamped
from std_msgs.msg import Float64


class Fusion:
    def __init__(self):
        path = rospkg.RosPack().get_path("course_fusion")
        with open(os.path.join(path, "config", "offset.txt")) as f:
            self.offset = float(f.read())
        self.gain = 1.0
        self.enabled = True
        self.pub = rospy.Publisher("fused", Float64, queue_size=10)
        self.server = Server(FusionConfig, self.reconfigure)
        left = message_filters.Subscriber("left", PointStamped)
        right = message_filters.Subscriber("right", PointStamped)
        self.sync = message_filters.ApproximateTimeSynchronizer([left, right], 10, 0.01)
        self.sync.registerCallback(self.fuse)

    def reconfigure(self, config, level):
        self.gain = config.gain
        self.enabled = config["enabled"]
        rospy.loginfo("gain %.1f enabled %s", self.gain, self.enabled)
        return config

    def fuse(self, left, right):
        if not self.enabled:
            return
        value = self.gain * (right.point.x - left.point.x) + self.offset
        self.pub.publish(Float64(value))
        rospy.loginfo("fused %.1f", value)


if __name__ == "__main__":
    rospy.init_node("fusion_node")
    Fusion()
    rospy.spin()
