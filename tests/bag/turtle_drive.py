"""A scripted turtle drive for tests/bag/test_turtle_replay.py (kame's rospy, run by the venv's
interpreter): segments of geometry_msgs/Twist streamed at 20 Hz on /turtle1/cmd_vel, as a
teleop would, then a single command that the turtle's 1 s timeout ends.

    python turtle_drive.py SUBSCRIBERS

waits until /turtle1/cmd_vel has SUBSCRIBERS subscribers (turtlesim and the recorder), drives,
and prints `done` after its last command (the turtle goes on for that command's 1 s).
"""

import sys
import time

import rospy
from geometry_msgs.msg import Twist

# (linear.x m/s, angular.z rad/s, seconds streamed at 20 Hz); 0 seconds: one message only
DRIVE = ((1.0, 0.0, 0.6), (1.0, 1.0, 0.8), (0.0, -1.5, 0.4), (0.8, 0.0, 0.0))
PERIOD = 0.05


def main() -> None:
    subscribers = int(sys.argv[1])
    rospy.init_node("turtle_drive", anonymous=True)
    pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=10)
    deadline = time.monotonic() + 10
    while pub.get_num_connections() < subscribers:
        if time.monotonic() > deadline:
            sys.exit(f"only {pub.get_num_connections()} subscribers on /turtle1/cmd_vel")
        time.sleep(0.02)
    time.sleep(0.3)  # the recorder's other subscriptions settle; some idle poses first
    tick = time.monotonic()
    for linear, angular, seconds in DRIVE:
        twist = Twist()
        twist.linear.x = linear
        twist.angular.z = angular
        for _ in range(max(1, round(seconds / PERIOD))):
            pub.publish(twist)
            tick += PERIOD
            time.sleep(max(0.0, tick - time.monotonic()))
    print("done", flush=True)


if __name__ == "__main__":
    main()
