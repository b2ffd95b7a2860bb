"""Debian's real dynamic_reconfigure Server (under /usr/bin/python3) with Debian's own TestConfig."""

from dynamic_reconfigure.cfg import TestConfig

import rospy
from dynamic_reconfigure.server import Server


def callback(config, level):
    print("configured int_={} str_={} level={}".format(config["int_"], config["str_"], level), flush=True)
    return config


if __name__ == "__main__":
    rospy.init_node("debian_reconfigure")
    server = Server(TestConfig, callback)
    rospy.spin()
