"""mimic: a turtle copies another's motion, as turtlesim's mimic does.

Node `turtle_mimic`: subscribes `input/pose` (turtlesim/Pose) and publishes `output/cmd_vel`
(Twist) with linear.x = linear_velocity and angular.z = angular_velocity. `input` and `output`
are namespaces that remap as roscpp's NodeHandle namespaces do:
`rosrun turtlesim mimic input:=turtlesim1/turtle1 output:=turtlesim2/turtle1`.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from geometry_msgs.msg import Twist
from kame.client import core, log, process, topics
from turtlesim.msg import Pose


def main(argv: Sequence[str] | None = None) -> int:
    log.use_roscpp_console()  # a C++ program in ROS
    process.init_node("turtle_mimic", argv=list(sys.argv if argv is None else argv))
    source = core.remap_name("input")
    target = core.remap_name("output")
    publisher = topics.Publisher(f"{target}/cmd_vel", Twist, queue_size=1)

    def on_pose(pose: Pose) -> None:
        twist = Twist()
        twist.angular.z = pose.angular_velocity
        twist.linear.x = pose.linear_velocity
        publisher.publish(twist)

    topics.Subscriber(f"{source}/pose", Pose, on_pose, queue_size=1)
    process.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
