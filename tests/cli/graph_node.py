"""A kame rospy node giving the ros* tool tests a graph to look at (turtlesim's interface, in small).

Publishes /turtle1/pose-like /chatter (std_msgs/String), subscribes /turtle1/cmd_vel
(geometry_msgs/Twist), and serves /spawn (turtlesim/Spawn), /clear (std_srvs/Empty),
/add_two_ints (rospy_tutorials/AddTwoInts), /set_flag (std_srvs/SetBool) and /fail
(std_srvs/Trigger, always raises).
Prints "ready" once everything is registered. Run as `python graph_node.py [__name:=x]`.
"""

from __future__ import annotations

import rospy
from geometry_msgs.msg import Twist
from rospy_tutorials.srv import AddTwoInts, AddTwoIntsResponse
from std_msgs.msg import String
from std_srvs.srv import Empty, EmptyResponse, SetBool, SetBoolResponse, Trigger
from turtlesim.srv import Spawn, SpawnResponse


def spawn(req: Spawn._request_class) -> SpawnResponse:  # type: ignore[name-defined]
    return SpawnResponse(name=req.name or "turtle2")


def fail(req: object) -> None:
    raise RuntimeError("it broke")


def main() -> None:
    rospy.init_node("graph_node")
    pub = rospy.Publisher("chatter", String, queue_size=10)
    rospy.Subscriber("turtle1/cmd_vel", Twist, lambda msg: None)
    rospy.Service("spawn", Spawn, spawn)
    rospy.Service("clear", Empty, lambda req: EmptyResponse())
    rospy.Service("add_two_ints", AddTwoInts, lambda req: AddTwoIntsResponse(req.a + req.b))
    rospy.Service("fail", Trigger, fail)
    rospy.Service("set_flag", SetBool, lambda req: SetBoolResponse(success=req.data, message=f"flag {req.data}"))
    print("ready", flush=True)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        pub.publish(String(data="hello"))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
