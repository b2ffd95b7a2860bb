"""rostopic.param_publish in a process of its own: publishes the message the parameter
/facade_msg holds on /facade_param, and again when the test changes it; prints what it hears."""

import queue
import threading

import rospy
import rostopic
from std_msgs.msg import String

pub, cls = rostopic.create_publisher("/facade_param", "std_msgs/String", latch=True)
rospy.set_param("/facade_msg", {"data": "p1"})
heard: "queue.Queue[str]" = queue.Queue()
rospy.Subscriber("/facade_param", String, lambda msg: heard.put(msg.data))
publishing = threading.Thread(target=rostopic.param_publish, args=(pub, cls, "/facade_msg", None, False))
publishing.start()
print("heard", heard.get(timeout=30), flush=True)
print("heard", heard.get(timeout=30), flush=True)
rospy.signal_shutdown("done")
publishing.join(10)
print("stopped", not publishing.is_alive(), flush=True)
