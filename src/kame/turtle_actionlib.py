"""turtle_actionlib's C++ programs, shape_server and shape_client (the actionlib tutorial with
turtlesim).

shape_server (node `turtle_shape`): serves the action named after its node (/turtle_shape,
turtle_actionlib/Shape). A goal (edges, radius) becomes a regular polygon of that many edges
inscribed in a circle of that radius, driven from where turtle1 stands: along each edge at
6 x the distance left, then turning at 6 x the angle left to the next edge's heading, each
to within 1e-5; every turtle1/pose brings one turtle1/cmd_vel. The result is the polygon's
interior angle and apothem; a cancel preempts. shape_client (node `test_shape`): waits for the
server, asks for a pentagon of radius 1.3 and waits up to 40 s for the result, saying how it
went, as the C++ programs log it.
"""

from __future__ import annotations

import math
import sys
import threading
from collections.abc import Sequence
from dataclasses import dataclass

from kame.client import core, log, process, topics
from kame.client.action.simple_action_client import SimpleActionClient
from kame.client.action.simple_action_server import SimpleActionServer

LINEAR_GAIN = 6.0
ANGULAR_GAIN = 6.0
TOLERANCE = 0.00001
STATE_NAMES = {0: "PENDING", 1: "ACTIVE", 2: "PREEMPTED", 3: "SUCCEEDED", 4: "ABORTED", 5: "REJECTED",
               6: "PREEMPTED", 7: "PENDING", 8: "RECALLED", 9: "LOST"}  # SimpleClientGoalState's names


def positive_angle(angle: float) -> float:
    """`angle` in [0, 2 pi), as angles::normalize_angle_positive."""
    return math.fmod(math.fmod(angle, 2 * math.pi) + 2 * math.pi, 2 * math.pi)


@dataclass
class Polygon:
    """A goal's polygon as the turtle drives it: pure, fed poses, giving velocity commands."""
    edges: int
    radius: float
    done_edges: int = 0
    start: tuple[float, float, float] | None = None  # where the current edge began (x, y, theta)

    @property
    def interior_angle(self) -> float:
        return (self.edges - 2) * math.pi / self.edges

    @property
    def apothem(self) -> float:
        return self.radius * math.cos(math.pi / self.edges)

    @property
    def side(self) -> float:
        return self.apothem * 2 * math.tan(math.pi / self.edges)

    @property
    def finished(self) -> bool:
        return self.done_edges >= self.edges

    def command(self, x: float, y: float, theta: float) -> tuple[float, float]:
        """(linear.x, angular.z) for the turtle at this pose."""
        if self.start is None:
            self.start = (x, y, theta)
        sx, sy, stheta = self.start
        distance_left = self.side - abs(math.hypot(sx - x, sy - y))
        turn_left = positive_angle(math.pi - self.interior_angle - (theta - stheta))
        if distance_left > TOLERANCE:
            return LINEAR_GAIN * distance_left, 0.0
        if abs(turn_left) > TOLERANCE:
            return 0.0, ANGULAR_GAIN * turn_left
        self.start = None
        self.done_edges += 1
        return 0.0, 0.0


def server_main(argv: Sequence[str] | None = None) -> int:
    from geometry_msgs.msg import Twist
    from turtle_actionlib.msg import ShapeAction, ShapeResult
    from turtlesim.msg import Pose

    log.use_roscpp_console()  # a C++ program in ROS
    process.init_node("turtle_shape", argv=list(sys.argv if argv is None else argv))
    name = core.get_name()
    server = SimpleActionServer(name, ShapeAction, auto_start=False)
    lock = threading.Lock()
    polygon: list[Polygon] = []  # the goal being driven
    publisher = topics.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)

    def on_goal() -> None:
        goal = server.accept_new_goal()
        with lock:
            polygon[:] = [Polygon(goal.edges, goal.radius)]

    def on_preempt() -> None:
        log.emit(log.INFO, "%s: Preempted", (name,))
        server.set_preempted()

    def on_pose(pose: Pose) -> None:
        if not server.is_active():
            return
        with lock:
            shape = polygon[0] if polygon else None
            if shape is None:
                return
            if shape.finished:
                log.emit(log.INFO, "%s: Succeeded", (name,))
                server.set_succeeded(ShapeResult(interior_angle=shape.interior_angle, apothem=shape.apothem))
                return
            twist = Twist()
            twist.linear.x, twist.angular.z = shape.command(pose.x, pose.y, pose.theta)
        publisher.publish(twist)

    server.register_goal_callback(on_goal)
    server.register_preempt_callback(on_preempt)
    topics.Subscriber("/turtle1/pose", Pose, on_pose, queue_size=1)
    server.start()
    process.spin()
    return 0


def client_main(argv: Sequence[str] | None = None) -> int:
    from kame.client.clock import Duration
    from turtle_actionlib.msg import ShapeAction, ShapeGoal

    log.use_roscpp_console()  # a C++ program in ROS
    process.init_node("test_shape", argv=list(sys.argv if argv is None else argv))
    client = SimpleActionClient("turtle_shape", ShapeAction)
    log.emit(log.INFO, "Waiting for action server to start.", ())
    if not client.wait_for_server():
        return 0  # shut down while waiting
    log.emit(log.INFO, "Action server started, sending goal.", ())
    client.send_goal(ShapeGoal(edges=5, radius=1.3))
    if client.wait_for_result(Duration.from_sec(40.0)):
        log.emit(log.INFO, "Action finished: %s", (STATE_NAMES.get(client.get_state(), "LOST"),))
    else:
        log.emit(log.INFO, "Action did not finish before the time out.", ())
    return 0
