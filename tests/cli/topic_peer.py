"""A kame rospy node giving the rostopic tests a graph: turtlesim's topics and a few more.

Publishes (fixed values, so that echo output can be pinned):
- /turtle1/pose (turtlesim/Pose) and /pose2d (geometry_msgs/Pose2D) at 20 Hz;
- /stamped (geometry_msgs/PointStamped) at 20 Hz, stamped now (for delay);
- latched: /js (sensor_msgs/JointState), /poses (geometry_msgs/PoseArray),
  /bytes (std_msgs/UInt8MultiArray), and with --custom /custom (kametest/Thing, a type
  from a user package on ROS_PACKAGE_PATH that the tool under test does not see).
Subscribes /turtle1/cmd_vel (geometry_msgs/Twist) and /chatter (std_msgs/String) and prints
each message it gets as one line (`cmd_vel 2.0 0.0 0.0 0.0 0.0 2.0`, `chatter hello`).
Prints "ready" once everything is registered.
"""

from __future__ import annotations

import sys

import rospy
from geometry_msgs.msg import Point, PointStamped, Pose, Pose2D, PoseArray, Quaternion, Twist
from sensor_msgs.msg import JointState
from std_msgs.msg import Header, String, UInt8MultiArray
from turtlesim.msg import Pose as TurtlePose

STAMP = rospy.Time(1795311367, 122221231)


def main() -> None:
    rospy.init_node("topic_peer")

    def on_twist(msg: Twist) -> None:
        values = (msg.linear.x, msg.linear.y, msg.linear.z, msg.angular.x, msg.angular.y, msg.angular.z)
        print("cmd_vel " + " ".join(str(float(v)) for v in values), flush=True)

    rospy.Subscriber("/turtle1/cmd_vel", Twist, on_twist)
    rospy.Subscriber("/chatter", String, lambda msg: print(f"chatter {msg.data}", flush=True))
    pose = rospy.Publisher("/turtle1/pose", TurtlePose, queue_size=10)
    pose2d = rospy.Publisher("/pose2d", Pose2D, queue_size=10)
    stamped = rospy.Publisher("/stamped", PointStamped, queue_size=10)
    js = rospy.Publisher("/js", JointState, latch=True, queue_size=1)
    js.publish(JointState(header=Header(stamp=STAMP, frame_id="base"), name=["a", "b"], position=[1.0, 2.5]))
    poses = rospy.Publisher("/poses", PoseArray, latch=True, queue_size=1)
    poses.publish(PoseArray(header=Header(stamp=STAMP, frame_id="map"), poses=[
        Pose(Point(1.0, 0.0, 0.0), Quaternion(0.0, 0.0, 0.0, 1.0)),
        Pose(Point(2.0, 3.0, 0.5), Quaternion(0.0, 0.0, 0.0, 1.0))]))
    raw = rospy.Publisher("/bytes", UInt8MultiArray, latch=True, queue_size=1)
    raw.publish(UInt8MultiArray(data=bytes([1, 2, 255])))
    if "--custom" in sys.argv:
        from kametest.msg import Thing  # type: ignore[import-not-found]

        custom = rospy.Publisher("/custom", Thing, latch=True, queue_size=1)
        custom.publish(Thing(name="widget", sizes=[3, 4], where=Point(1.0, 2.0, 3.0)))
    print("ready", flush=True)
    rate = rospy.Rate(20)
    while not rospy.is_shutdown():
        pose.publish(TurtlePose(x=5.544444561004639, y=5.544444561004639, theta=0.0))
        pose2d.publish(Pose2D(x=1.5, y=2.0, theta=0.25))
        stamped.publish(PointStamped(header=Header(stamp=rospy.Time.now(), frame_id="odom"), point=Point(1, 2, 3)))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
