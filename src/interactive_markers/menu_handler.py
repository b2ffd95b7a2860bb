"""interactive_markers.menu_handler: kame.interactive_markers.menu under its ROS name."""

import rospy
from kame.interactive_markers.menu import CHECKED, NO_CHECKBOX, UNCHECKED, MenuHandler
from visualization_msgs.msg import InteractiveMarkerFeedback, MenuEntry

# as `from interactive_markers.menu_handler import *` in ROS: its imports and MenuHandler
__all__ = ["CHECKED", "NO_CHECKBOX", "UNCHECKED", "InteractiveMarkerFeedback", "MenuEntry", "MenuHandler", "rospy"]
