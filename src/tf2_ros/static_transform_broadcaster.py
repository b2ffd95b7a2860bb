"""tf2_ros.StaticTransformBroadcaster: latched /tf_static. A latch keeps one message, so all the
static transforms this process sends, through any number of broadcasters, are merged into one
message (a newer transform of the same child frame replaces the older) and sent whole."""

import threading

import rospy
from tf2_msgs.msg import TFMessage

_lock = threading.Lock()
_by_child = {}  # the process's static transforms, by child frame


class StaticTransformBroadcaster:
    def __init__(self, queue_size=100):
        self.pub_tf = rospy.Publisher("/tf_static", TFMessage, queue_size=queue_size, latch=True)

    def sendTransform(self, transform):
        if not isinstance(transform, list):
            transform = [transform]
        with _lock:
            for item in transform:
                _by_child[item.child_frame_id] = item
            self.pub_tf.publish(TFMessage(list(_by_child.values())))
