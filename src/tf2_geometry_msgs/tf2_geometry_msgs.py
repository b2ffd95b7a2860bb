"""do_transform_point/vector3/pose/pose_with_covariance_stamped/wrench (kame.tf.geometry),
registered with tf2_ros.TransformRegistration, and the identity message conversions."""

import tf2_ros
from geometry_msgs.msg import PointStamped, PoseStamped, PoseWithCovarianceStamped, Vector3Stamped, WrenchStamped
from kame.tf.geometry import (
    do_transform_point,
    do_transform_pose,
    do_transform_pose_with_covariance_stamped,
    do_transform_vector3,
    do_transform_wrench,
)

__all__ = ["do_transform_point", "do_transform_pose", "do_transform_pose_with_covariance_stamped",
           "do_transform_vector3", "do_transform_wrench", "from_msg_msg", "to_msg_msg"]


def to_msg_msg(msg):
    return msg


def from_msg_msg(msg):
    return msg


for _type in (Vector3Stamped, PoseStamped, PointStamped):
    tf2_ros.ConvertRegistration().add_to_msg(_type, to_msg_msg)
    tf2_ros.ConvertRegistration().add_from_msg(_type, from_msg_msg)
for _type, _function in ((PointStamped, do_transform_point), (Vector3Stamped, do_transform_vector3),
                         (PoseStamped, do_transform_pose), (PoseWithCovarianceStamped,
                                                            do_transform_pose_with_covariance_stamped),
                         (WrenchStamped, do_transform_wrench)):
    tf2_ros.TransformRegistration().add(_type, _function)
