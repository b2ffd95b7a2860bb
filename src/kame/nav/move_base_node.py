"""move_base, the node: drives a robot to a goal on a map with two costmaps, navfn's plan, a
DWA local planner and move_base's recovery behaviours.

    rosrun move_base move_base

As navigation's move_base: the `move_base` action (move_base_msgs/MoveBase) and
`move_base_simple/goal` (geometry_msgs/PoseStamped) take goals in the global frame;
`~make_plan` (nav_msgs/GetPlan) plans without moving; `~clear_costmaps` (std_srvs/Empty)
forgets what the sensors marked; `cmd_vel` carries the commands. Published for rviz:
`~global_costmap/costmap`, `~local_costmap/costmap` and their `footprint`s (kame.nav.costmap_ros),
`~NavfnROS/plan` (the global plan), `~DWAPlannerROS/local_plan` and `~DWAPlannerROS/global_plan`
(or TrajectoryPlannerROS/..., after ~base_local_planner). The parameters are
turtlebot_navigation's YAML layout (kame.nav.config).

The state machine is move_base's: PLANNING until a plan is found (for at most planner_patience
seconds), CONTROLLING while the local planner finds commands (a failure replans; one lasting
controller_patience seconds, or oscillation, goes to CLEARING), CLEARING runs the next recovery
behaviour (conservative_reset, rotate_recovery, aggressive_reset, rotate_recovery by default, or
~recovery_behaviors) and plans again; with none left the goal is aborted with move_base's text.
What kame's move_base adds: a goal is checked before it is planned for: one whose position is NaN
or inf is aborted as one with a bad quaternion is, and one off the global costmap is aborted
at once saying so (move_base tried, recovered and aborted with "Failed to find a valid plan");
a map or scan that cannot be used is left out with one line (kame.nav.inputs).
What kame's move_base does not have: the local planner checks the robot's inscribed circle, not
every edge of a polygon footprint; PointCloud2 observation sources (the TurtleBot's bumper) are
not read.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from typing import Any

import numpy as np

from kame.client import clock, core, process, services, timer, topics
from kame.client import log as _log
from kame.client.action.simple_action_server import SimpleActionServer
from kame.client.errors import ROSInterruptException
from kame.nav import inputs
from kame.nav.amcl_node import yaw_of
from kame.nav.config import (
    CLEAR,
    ConfigError,
    CostmapConfig,
    MoveBaseConfig,
    Recovery,
    costmap_config,
    local_planner_params,
    move_base_config,
)
from kame.nav.costmap import footprint_hits_lethal
from kame.nav.costmap_ros import CostmapROS
from kame.nav.local_planner import choose_trajectory, rotate_toward
from kame.nav.planner import make_plan
from kame.net.signal_wake import SignalSafeEvent
from kame.tf_ros.buffer import Buffer
from kame.tf_ros.node_io import TransformListener

Pose2D = tuple[float, float, float]
ABORT_TEXT = {
    "planning": ("Aborting because a valid plan could not be found. Even after executing all recovery behaviors",
                 "Failed to find a valid plan. Even after executing recovery behaviors."),
    "controlling": ("Aborting because a valid control could not be found. Even after executing all recovery "
                    "behaviors", "Failed to find a valid control. Even after executing recovery behaviors."),
    "oscillation": ("Aborting because the robot appears to be oscillating over and over. Even after executing "
                    "all recovery behaviors", "Robot is oscillating. Even after executing recovery behaviors."),
}


def _param(name: str, default: Any) -> Any:
    return process.get_param("~" + name, default)


def _path_msg(frame: str, points: Any) -> Any:
    from geometry_msgs.msg import PoseStamped
    from nav_msgs.msg import Path
    msg = Path()
    msg.header.frame_id = frame
    msg.header.stamp = clock.get_rostime()
    for px, py in points:
        pose = PoseStamped()
        pose.header.frame_id = frame
        pose.pose.position.x, pose.pose.position.y = float(px), float(py)
        pose.pose.orientation.w = 1.0
        msg.poses.append(pose)
    return msg


class MoveBase:
    def __init__(self, config: MoveBaseConfig, global_config: CostmapConfig, local_config: CostmapConfig) -> None:
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Path
        self.config = config
        self.planner = local_planner_params(_param, config.local_planner_name, config.controller_frequency)
        self.allow_unknown = bool(_param(f"{config.global_planner_name}/allow_unknown", True))
        self.velocity = (0.0, 0.0)
        self.scans: dict[str, Any] = {}  # the newest scan of each observed topic
        self.map_ready = SignalSafeEvent()  # the main thread waits on it
        node = core.get_node()
        assert node is not None
        self.buffer = Buffer(warn=lambda text: _log.emit(_log.WARN, text, ()))
        self.listener = TransformListener(node, self.buffer, now=lambda: clock.get_rostime().to_nsec())
        self.global_costmap = CostmapROS(global_config, self.buffer)
        self.local_costmap = CostmapROS(local_config, self.buffer)
        self.cmd_vel = topics.Publisher("cmd_vel", Twist, queue_size=1)
        self.plan_pub = topics.Publisher(f"~{config.global_planner_name}/plan", Path, queue_size=1)
        local = config.local_planner_name
        self.local_plan_pub = topics.Publisher(f"~{local}/local_plan", Path, queue_size=1)
        self.local_global_plan_pub = topics.Publisher(f"~{local}/global_plan", Path, queue_size=1)

    # ---------------------------------------------------------------- inputs

    def on_map(self, msg: Any) -> None:
        self.global_costmap.on_map(msg)
        self.local_costmap.on_map(msg)  # a local costmap that does not roll is the map's too
        self.map_ready.set()

    def on_scan(self, topic: str, scan: Any) -> None:
        problem = inputs.scan_problem(scan)
        if problem is not None:
            _log.emit_throttle(10.0, _log.WARN, "Ignoring a scan on %s: %s", (topic, problem))
            return
        self.scans[topic] = scan

    def update_costmaps(self) -> None:
        now = clock.get_time()
        scans = dict(self.scans)
        for costmap in (self.global_costmap, self.local_costmap):
            costmap.update(now, scans)

    # ---------------------------------------------------------------- planning

    def plan(self, start: tuple[float, float], goal: tuple[float, float]) -> list[tuple[float, float]] | None:
        with self.global_costmap.lock:
            if self.global_costmap.costmap is None:
                return None
            return make_plan(self.global_costmap.costmap, start, goal, self.allow_unknown)

    def make_plan_service(self, request: Any) -> Any:
        from nav_msgs.srv import GetPlanResponse
        start = request.start.pose.position
        start_xy: tuple[float, float] | None = (start.x, start.y)
        if not request.start.header.frame_id:  # as move_base: no start frame means where the robot is
            pose = self.global_costmap.robot_pose()
            start_xy = None if pose is None else pose[:2]
        goal = request.goal.pose.position
        path = None if start_xy is None else self.plan(start_xy, (goal.x, goal.y))
        response = GetPlanResponse()
        response.plan = _path_msg(self.global_costmap.config.global_frame, path or [])
        return response

    def clear_costmaps_service(self, request: Any) -> Any:
        from std_srvs.srv import EmptyResponse
        self.global_costmap.clear()
        self.local_costmap.clear()
        return EmptyResponse()

    def send(self, linear: float, angular: float) -> None:
        from geometry_msgs.msg import Twist
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        self.velocity = (linear, angular)
        self.cmd_vel.publish(twist)

    # ---------------------------------------------------------------- the state machine

    def execute(self, server: SimpleActionServer, goal: Any) -> None:
        try:
            self._execute(server, goal)
        except ROSInterruptException:
            pass

    def _execute(self, server: SimpleActionServer, goal: Any) -> None:
        target = goal.target_pose
        q = target.pose.orientation
        refusal = self._refusal(target)
        if refusal is not None:
            server.set_aborted(text=refusal)
            return
        global_frame = self.global_costmap.config.global_frame
        goal_pose = (target.pose.position.x, target.pose.position.y, yaw_of(q))
        config = self.config
        rate = timer.Rate(config.controller_frequency)
        state, trigger, recovery_index = "planning", "", 0
        path: list[tuple[float, float]] | None = None
        now = clock.get_time()
        last_valid_plan = last_valid_control = last_oscillation_reset = now
        next_plan = now
        planning_retries = 0
        oscillation_pose: Pose2D | None = None
        while not core.is_shutdown():
            if server.is_preempt_requested():
                self.send(0.0, 0.0)
                server.set_preempted()
                return
            now = clock.get_time()
            pose = self.global_costmap.robot_pose()
            if pose is None:
                self.send(0.0, 0.0)
                rate.sleep()
                continue
            if oscillation_pose is None or math.dist(pose[:2], oscillation_pose[:2]) >= config.oscillation_distance:
                oscillation_pose, last_oscillation_reset = pose, now
                if trigger == "oscillation":
                    recovery_index = 0
            if state == "planning" or (state == "controlling" and config.planner_frequency > 0 and now >= next_plan):
                next_plan = now + (1.0 / config.planner_frequency if config.planner_frequency > 0 else 0.0)
                found = self.plan(pose[:2], goal_pose[:2])
                if found is not None:
                    path, last_valid_plan, planning_retries = found, now, 0
                    self.plan_pub.publish(_path_msg(global_frame, found))
                    state = "controlling"
                    if trigger == "planning":
                        recovery_index = 0
                else:
                    planning_retries += 1
                    out_of_retries = 0 <= config.max_planning_retries < planning_retries
                    if now > last_valid_plan + config.planner_patience or out_of_retries:
                        self.send(0.0, 0.0)
                        state, trigger = "clearing", "planning"
                    elif state == "planning":
                        self.send(0.0, 0.0)
            if state == "controlling":
                assert path is not None
                if self._goal_reached(pose, goal_pose):
                    self.send(0.0, 0.0)
                    server.set_succeeded(text="Goal reached.")
                    return
                if config.oscillation_timeout > 0 and now > last_oscillation_reset + config.oscillation_timeout:
                    self.send(0.0, 0.0)
                    state, trigger = "clearing", "oscillation"
                elif self._control(pose, goal_pose, path):
                    last_valid_control = now
                    if trigger == "controlling":
                        recovery_index = 0
                elif now > last_valid_control + config.controller_patience:
                    self.send(0.0, 0.0)
                    state, trigger = "clearing", "controlling"
                else:
                    self.send(0.0, 0.0)
                    state = "planning"  # as move_base: no valid command, so plan again
            if state == "clearing":
                if config.recovery_behavior_enabled and recovery_index < len(config.recoveries):
                    self._recover(config.recoveries[recovery_index], server)
                    recovery_index += 1
                    now = clock.get_time()
                    last_valid_plan = last_valid_control = last_oscillation_reset = now
                    planning_retries = 0
                    state = "planning"
                else:
                    log_text, result_text = ABORT_TEXT[trigger]
                    _log.emit(_log.ERROR, "%s", (log_text,))
                    self.send(0.0, 0.0)
                    server.set_aborted(text=result_text)
                    return
            rate.sleep()

    def _refusal(self, target: Any) -> str | None:
        """Why a goal (a PoseStamped) is aborted before any planning, with its error logged; None
        for a goal to plan for."""
        problem = inputs.position_problem(target.pose.position)
        if problem is not None:
            _log.emit(_log.ERROR, "%s", (problem,))
            return "Aborting on goal because it was sent with a position that has nans or infs"
        problem = inputs.quaternion_problem(target.pose.orientation)
        if problem is not None:
            _log.emit(_log.ERROR, "%s", (problem,))
            return "Aborting on goal because it was sent with an invalid quaternion"
        global_frame = self.global_costmap.config.global_frame
        frame = target.header.frame_id.lstrip("/")
        if frame and frame != global_frame:
            return f"goals must be given in the global frame [{global_frame}], not [{frame}]"
        x, y = target.pose.position.x, target.pose.position.y
        with self.global_costmap.lock:
            costmap = self.global_costmap.costmap
            if costmap is None or costmap.cell_of(x, y) is not None:
                return None
            x0, y0, x1, y1 = costmap.bounds()
        _log.emit(_log.WARN, "The goal sent to the navfn planner is off the global costmap. Planning will always "
                             "fail to this goal.", ())
        return (f"Aborting on goal because it is off the global costmap: ({x:g}, {y:g}) is outside "
                f"[{x0:g}, {x1:g}] x [{y0:g}, {y1:g}] in {global_frame}")

    def _goal_reached(self, pose: Pose2D, goal: Pose2D) -> bool:
        within = math.hypot(pose[0] - goal[0], pose[1] - goal[1]) <= self.planner.xy_goal_tolerance
        return within and abs(math.remainder(goal[2] - pose[2], 2 * math.pi)) <= self.planner.yaw_goal_tolerance

    def _control(self, pose: Pose2D, goal: Pose2D, path: list[tuple[float, float]]) -> bool:
        """One cycle of the local planner on the local costmap (in its frame); False when no
        trajectory is free."""
        if math.hypot(pose[0] - goal[0], pose[1] - goal[1]) <= self.planner.xy_goal_tolerance:
            self.send(0.0, rotate_toward(pose[2], goal[2], self.planner))  # at the spot: turn to the heading
            return True
        local_pose = self.local_costmap.robot_pose()
        if local_pose is None:
            return False
        # the plan in the local costmap's frame: through the robot, seen from both frames
        seen = np.asarray(path, dtype=float)
        c, s = math.cos(pose[2]), math.sin(pose[2])
        dx, dy = seen[:, 0] - pose[0], seen[:, 1] - pose[1]
        bx, by = c * dx + s * dy, -s * dx + c * dy
        lc, ls = math.cos(local_pose[2]), math.sin(local_pose[2])
        local_path = np.column_stack((local_pose[0] + lc * bx - ls * by, local_pose[1] + ls * bx + lc * by))
        frame = self.local_costmap.config.global_frame
        with self.local_costmap.lock:
            assert self.local_costmap.costmap is not None
            best = choose_trajectory(self.local_costmap.costmap, local_pose, self.velocity,
                                     local_path.tolist(), self.planner)
        self.local_global_plan_pub.publish(_path_msg(frame, local_path))
        if best is None:
            _log.emit(_log.WARN, "DWA planner failed to produce path.", ())
            return False
        self.local_plan_pub.publish(_path_msg(frame, best.points))
        self.send(best.linear, best.angular)
        return True

    # ---------------------------------------------------------------- recovery behaviours

    def _recover(self, recovery: Recovery, server: SimpleActionServer) -> None:
        pose = self.global_costmap.robot_pose()
        if recovery.kind == CLEAR:
            _log.emit(_log.WARN, "Clearing both costmaps outside a square (%.2fm) large centered on the robot.",
                      (recovery.reset_distance,))
            for costmap in (self.global_costmap, self.local_costmap):
                here = costmap.robot_pose()
                if here is not None:
                    costmap.clear(here[:2], recovery.reset_distance)
            return
        if pose is not None:
            self._rotate(recovery, server)

    def _rotate(self, recovery: Recovery, server: SimpleActionServer) -> None:
        """rotate_recovery: a full turn on the spot, unless the local costmap says the robot
        cannot turn where it stands."""
        _log.emit(_log.WARN, "Rotate recovery behavior started.", ())
        ns = "TrajectoryPlannerROS/"  # rotate_recovery reads these from the base local planner's old namespace
        max_rot = float(_param(ns + "max_rotational_vel", 1.0))
        min_rot = float(_param(ns + "min_in_place_rotational_vel", 0.4))
        acc = float(_param(ns + "acc_lim_th", 3.2))
        tolerance = float(_param(ns + "yaw_goal_tolerance", 0.10))
        rate = timer.Rate(float(_param(recovery.name + "/frequency", 20.0)))
        turned = 0.0
        last = self.local_costmap.robot_pose()
        while last is not None and not core.is_shutdown() and not server.is_preempt_requested():
            left = 2 * math.pi - turned
            if left < tolerance:
                break
            with self.local_costmap.lock:  # the footprint where the turn takes it in the next half second
                costmap = self.local_costmap.costmap
                assert costmap is not None
                cost = footprint_hits_lethal(costmap, (last[0], last[1], last[2] + min(left, 0.5)),
                                             self.local_costmap.footprint)
            if cost is not None:
                _log.emit(_log.ERROR, "Rotate recovery can't rotate in place because there is a potential "
                                      "collision. Cost: %.2f", (float(cost),))
                break
            speed = max(min_rot, min(max_rot, math.sqrt(2 * acc * left)))
            self.send(0.0, speed)
            rate.sleep()
            now = self.local_costmap.robot_pose()
            if now is None:
                break
            turned += abs(math.remainder(now[2] - last[2], 2 * math.pi))
            last = now
        self.send(0.0, 0.0)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    _log.use_roscpp_console()
    process.init_node("move_base", argv=argv)
    from geometry_msgs.msg import PoseStamped
    from move_base_msgs.msg import MoveBaseAction, MoveBaseActionGoal
    from nav_msgs.msg import OccupancyGrid
    from nav_msgs.srv import GetPlan
    from sensor_msgs.msg import LaserScan
    from std_srvs.srv import Empty

    try:
        global_config = costmap_config(_param, "global_costmap")
        local_config = costmap_config(_param, "local_costmap")
        config = move_base_config(_param, global_config.circumscribed_radius)
    except ConfigError as exc:
        _log.emit(_log.FATAL, "%s", (exc,))
        core.signal_shutdown("bad parameters")
        return 1
    move_base = MoveBase(config, global_config, local_config)
    topics.Subscriber("map", OccupancyGrid, move_base.on_map, queue_size=1)
    observed: set[str] = set()
    for source in global_config.sources + local_config.sources:
        if source.data_type != "LaserScan" and source.topic not in observed:
            observed.add(source.topic)
            _log.emit(_log.WARN, "kame's move_base reads LaserScan observation sources only; %s (%s on %s) "
                                 "is not read", (source.name, source.data_type, source.topic))
        elif source.topic not in observed:
            observed.add(source.topic)
            topics.Subscriber(source.topic, LaserScan, lambda scan, topic=source.topic: move_base.on_scan(topic, scan),
                              queue_size=1)
    if global_config.static_map:  # as move_base's global costmap, take goals only once the static map is in
        _log.emit(_log.INFO, "Requesting the map...", ())
        with core.woken_at_shutdown(move_base.map_ready):
            move_base.map_ready.wait()
        if core.is_shutdown():
            return 0
    server = SimpleActionServer("move_base", MoveBaseAction,
                                execute_cb=lambda goal: move_base.execute(server, goal), auto_start=False)
    server.start()
    goals = topics.Publisher("move_base/goal", MoveBaseActionGoal, queue_size=1)

    def simple_goal(pose: Any) -> None:
        action_goal = MoveBaseActionGoal()
        action_goal.header.stamp = clock.get_rostime()
        action_goal.goal.target_pose = pose
        goals.publish(action_goal)

    topics.Subscriber("move_base_simple/goal", PoseStamped, simple_goal, queue_size=1)
    services.Service("~make_plan", GetPlan, move_base.make_plan_service)
    services.Service("~clear_costmaps", Empty, move_base.clear_costmaps_service)
    # the main thread keeps the costmaps (costmap_2d's map update loop)
    fastest = max(global_config.update_frequency, local_config.update_frequency, 1.0)
    rate = timer.Rate(fastest)
    try:
        while not core.is_shutdown():
            move_base.update_costmaps()
            rate.sleep()
    except KeyboardInterrupt:  # Ctrl-C, or rospy's ROSInterruptException at shutdown
        core.signal_shutdown("keyboard interrupt")
    return 0
