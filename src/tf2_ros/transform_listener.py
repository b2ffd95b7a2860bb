"""tf2_ros.TransformListener: /tf and /tf_static into a Buffer, with the publisher's callerid as
the authority; a ROS clock that went back clears the buffer."""

import rospy
from tf2_msgs.msg import TFMessage


class TransformListener:
    def __init__(self, buffer, queue_size=None, buff_size=65536, tcp_nodelay=False):
        self.buffer = buffer
        self.tf_sub = rospy.Subscriber("/tf", TFMessage, self.callback, queue_size=queue_size,
                                       buff_size=buff_size, tcp_nodelay=tcp_nodelay)
        self.tf_static_sub = rospy.Subscriber("/tf_static", TFMessage, self.static_callback, queue_size=queue_size,
                                              buff_size=buff_size, tcp_nodelay=tcp_nodelay)

    def unregister(self):
        self.tf_sub.unregister()
        self.tf_static_sub.unregister()

    def _receive(self, data, is_static):
        who = (getattr(data, "_connection_header", None) or {}).get("callerid", "default_authority")
        receive_at = getattr(self.buffer, "receive_at", None)  # kame's Buffer; a user's buffer has the setters
        if receive_at is not None:
            receive_at(data.transforms, who, is_static, _now_ns)
            return
        setter = self.buffer.set_transform_static if is_static else self.buffer.set_transform
        for transform in data.transforms:
            setter(transform, who)

    def callback(self, data):
        self._receive(data, False)

    def static_callback(self, data):
        self._receive(data, True)


def _now_ns():
    return rospy.Time.now().to_nsec()
