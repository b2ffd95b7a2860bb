"""tf.TransformBroadcaster: the first tf API's sendTransform(translation, rotation, time, child,
parent), sent as tf2 on /tf."""

import geometry_msgs.msg
import tf2_ros.transform_broadcaster


class TransformBroadcaster:
    def __init__(self, queue_size=100):
        self.tf2_broadcaster = tf2_ros.transform_broadcaster.TransformBroadcaster(queue_size)

    def sendTransform(self, translation, rotation, time, child, parent):
        """Broadcast the pose of frame `child` in frame `parent`: translation (x, y, z), rotation
        quaternion (x, y, z, w), at `time` (a rospy.Time)."""
        t = geometry_msgs.msg.TransformStamped()
        t.header.frame_id = parent
        t.header.stamp = time
        t.child_frame_id = child
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = translation[:3]
        (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
         t.transform.rotation.w) = rotation[:4]
        self.sendTransformMessage(t)

    def sendTransformMessage(self, transform):
        self.tf2_broadcaster.sendTransform([transform])
