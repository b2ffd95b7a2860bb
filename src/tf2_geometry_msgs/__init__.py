"""tf2_geometry_msgs: do_transform_* for the stamped geometry_msgs types, registered with
tf2_ros so Buffer.transform() takes them."""

from .tf2_geometry_msgs import *  # noqa: F403 -- the package is its module, as in ROS
