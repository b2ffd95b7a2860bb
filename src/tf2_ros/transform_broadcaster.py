"""tf2_ros.TransformBroadcaster: TransformStamped (one or a list) on /tf."""

import rospy
from tf2_msgs.msg import TFMessage


class TransformBroadcaster:
    def __init__(self, queue_size=100):
        self.pub_tf = rospy.Publisher("/tf", TFMessage, queue_size=queue_size)

    def sendTransform(self, transform):
        if not isinstance(transform, list):
            transform = [transform]
        self.pub_tf.publish(TFMessage(transform))
