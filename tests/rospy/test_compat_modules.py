"""genpy and roslib as ROS code imports them."""

from __future__ import annotations

import io

import pytest

import genpy
import genpy.dynamic
import genpy.message
import roslib
import roslib.message
import rospy


def test_genpy_names() -> None:
    from geometry_msgs.msg import Twist

    assert isinstance(Twist(), genpy.Message)
    assert issubclass(rospy.Time, genpy.Time) and issubclass(rospy.Duration, genpy.Duration)
    assert genpy.Time(1, 5) + genpy.Duration(1) == genpy.Time(2, 5)
    assert genpy.message.strify_message(Twist()).startswith("linear: \n  x: 0.0")
    assert issubclass(genpy.SerializationError, genpy.MessageException)
    String = genpy.dynamic.generate_dynamic("std_msgs/String", "string data\n")["std_msgs/String"]
    buff = io.BytesIO()
    String(data="hi").serialize(buff)
    assert buff.getvalue() == b"\x02\x00\x00\x00hi"


def test_roslib_lookups() -> None:
    roslib.load_manifest("beginner_tutorials")  # a no-op in catkin-era ROS
    from std_srvs.srv import SetBool

    assert roslib.message.get_message_class("std_msgs/String")._type == "std_msgs/String"
    assert roslib.message.get_message_class("Header")._type == "std_msgs/Header"
    assert roslib.message.get_service_class("std_srvs/SetBool") is SetBool
    assert roslib.message.get_message_class("no_such_pkg/Nope") is None
    with pytest.raises(ValueError, match="missing package name"):  # genpy's, through roslib's
        roslib.message.get_message_class("malformed")


def test_importing_a_package_brings_its_modules_as_in_ros() -> None:
    """`import rospy` then `rospy.core.is_shutdown()` (and the like) works, as with ROS's packages."""
    import subprocess
    import sys

    code = (
        "import rospy, actionlib, rosbag, roslaunch\n"
        "rospy.core.is_shutdown, rospy.client.init_node, rospy.rostime.Time, rospy.topics.Publisher\n"
        "rospy.service.ServiceException, rospy.exceptions.ROSException, rospy.timer.Rate, rospy.msg.AnyMsg\n"
        "actionlib.action_client.ActionClient, actionlib.simple_action_server.SimpleActionServer\n"
        "rosbag.bag.Bag, roslaunch.parent.ROSLaunchParent, roslaunch.scriptapi.ROSLaunch, roslaunch.core.Node\n"
        "assert rospy.rostime.Time is rospy.Time and rospy.msg.AnyMsg is rospy.AnyMsg\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
