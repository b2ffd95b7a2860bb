"""draw_square: turtle1 draws a 2 m square forever, as turtlesim's draw_square does.

Node `draw_square`: calls `reset` once, subscribes `turtle1/pose`, publishes `turtle1/cmd_vel`;
a 16 ms timer runs the state machine FORWARD (1.0 m/s until within 0.1 m of a goal 2 m ahead),
STOP_FORWARD, TURN (0.4 rad/s until the heading is +90 degrees, within 0.01 rad), STOP_TURN,
logging `New goal [x y, theta]` and `Reached goal`.
"""

from __future__ import annotations

import enum
import math
import sys
from collections.abc import Sequence
from typing import Any

from geometry_msgs.msg import Twist
from kame.client import clock, errors, log, process, services, timer, topics
from std_srvs.srv import Empty
from turtlesim.msg import Pose

PI = 3.141592  # draw_square.cpp's own


class State(enum.Enum):
    FORWARD = 0
    STOP_FORWARD = 1
    TURN = 2
    STOP_TURN = 3


class Goal:
    def __init__(self) -> None:
        self.x = self.y = self.theta = 0.0


class SquareDriver:
    """The state machine, fed poses and asked for a command every tick (None: send nothing)."""

    def __init__(self) -> None:
        self.pose: Any = None
        self.goal = Goal()
        self.state = State.FORWARD
        self.first_goal_set = False

    def _reached(self) -> bool:
        p, g = self.pose, self.goal
        return bool(abs(p.x - g.x) < 0.1 and abs(p.y - g.y) < 0.1 and abs(p.theta - g.theta) < 0.01)

    def _stopped(self) -> bool:
        return bool(self.pose.angular_velocity < 0.0001 and self.pose.linear_velocity < 0.0001)

    def _goal_ahead(self) -> None:
        p = self.pose
        self.goal.x = math.cos(p.theta) * 2 + p.x
        self.goal.y = math.sin(p.theta) * 2 + p.y
        self.goal.theta = p.theta
        log.emit(log.INFO, "New goal [%f %f, %f]", (self.goal.x, self.goal.y, self.goal.theta))

    def tick(self) -> tuple[float, float] | None:
        if self.pose is None:
            return None
        if not self.first_goal_set:
            self.first_goal_set = True
            self.state = State.FORWARD
            self._goal_ahead()
        if self.state is State.FORWARD:
            if self._reached():
                self.state = State.STOP_FORWARD
                return 0.0, 0.0
            return 1.0, 0.0
        if self.state is State.TURN:
            if self._reached():
                self.state = State.STOP_TURN
                return 0.0, 0.0
            return 0.0, 0.4
        if not self._stopped():
            return 0.0, 0.0
        log.emit(log.INFO, "Reached goal", ())
        if self.state is State.STOP_FORWARD:
            self.state = State.TURN
            self.goal.x, self.goal.y = self.pose.x, self.pose.y
            theta = math.fmod(self.pose.theta + PI / 2.0, 2 * PI)
            if theta >= PI:
                theta -= 2 * PI
            self.goal.theta = theta
            log.emit(log.INFO, "New goal [%f %f, %f]", (self.goal.x, self.goal.y, self.goal.theta))
        else:
            self.state = State.FORWARD
            self._goal_ahead()
        return None


def main(argv: Sequence[str] | None = None) -> int:
    log.use_roscpp_console()  # a C++ program in ROS
    process.init_node("draw_square", argv=list(sys.argv if argv is None else argv))
    driver = SquareDriver()

    def on_pose(pose: Pose) -> None:
        driver.pose = pose

    topics.Subscriber("turtle1/pose", Pose, on_pose, queue_size=1)
    publisher = topics.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
    reset = services.ServiceProxy("reset", Empty)
    try:
        services.wait_for_service("reset", timeout=5.0)  # kame: a launch may start us before turtlesim
        reset()
    except (errors.ROSException, services.ServiceException):
        pass

    def on_timer(_event: Any) -> None:
        command = driver.tick()
        if command is not None:
            twist = Twist()
            twist.linear.x, twist.angular.z = command
            publisher.publish(twist)

    timer.Timer(clock.Duration(0.016), on_timer)
    process.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
