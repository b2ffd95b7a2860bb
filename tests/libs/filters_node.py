"""A ROS node for message_filters' live tests, run by kame's or Debian's interpreter.

`pub`: publishes geometry_msgs/PointStamped on /left and /right at 20 Hz, the same stamp on
both with /right 2 ms later. `sub`: message_filters.Subscriber on both into an
ApproximateTimeSynchronizer (slop 10 ms) and prints "synced <x> <y>" for three pairs, then exits.
"""

import sys

import message_filters
import rospy
from geometry_msgs.msg import PointStamped


def publish() -> None:
    rospy.init_node("filters_pub")
    left = rospy.Publisher("left", PointStamped, queue_size=10)
    right = rospy.Publisher("right", PointStamped, queue_size=10)
    rate = rospy.Rate(20)
    count = 0
    while not rospy.is_shutdown():
        stamp = rospy.Time.now()
        msg = PointStamped()
        msg.header.stamp = stamp
        msg.point.x = count
        left.publish(msg)
        msg.header.stamp = stamp + rospy.Duration(0, 2_000_000)
        msg.point.x = count + 0.5
        right.publish(msg)
        count += 1
        rate.sleep()


def subscribe() -> None:
    rospy.init_node("filters_sub")
    pairs = []
    left = message_filters.Subscriber("left", PointStamped)
    right = message_filters.Subscriber("right", PointStamped, queue_size=5)
    sync = message_filters.ApproximateTimeSynchronizer([left, right], 10, 0.01)

    def synced(a: PointStamped, b: PointStamped) -> None:
        pairs.append((a.point.x, b.point.x))
        print("synced", a.point.x, b.point.x, flush=True)
        if len(pairs) == 3:
            rospy.signal_shutdown("done")

    sync.registerCallback(synced)
    print("topics", left.getTopic(), right.name, flush=True)
    rospy.spin()


if __name__ == "__main__":
    publish() if sys.argv[1] == "pub" else subscribe()
