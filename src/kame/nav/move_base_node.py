"""move_base, the node: drives a robot to a goal on a map with a costmap, navfn's plan and DWA.

    rosrun move_base move_base

As navigation's move_base: the `move_base` action (move_base_msgs/MoveBase) and
`move_base_simple/goal` (geometry_msgs/PoseStamped) take goals in the global frame;
`~make_plan` (nav_msgs/GetPlan) plans without moving; `cmd_vel` carries the commands;
`~global_costmap/costmap` (nav_msgs/OccupancyGrid) and `~NavfnROS/plan` (nav_msgs/Path) show
the costmap and the plan. The map comes from `map` (latched, as map_server publishes it); the
robot's pose from tf (~global_costmap/global_frame -> ~global_costmap/robot_base_frame); the
obstacle layer's observations from the LaserScan topic ~global_costmap/obstacle_layer/scan/topic
(default `scan`). A goal with no plan is aborted; when no trajectory is free, the costmap's
sensor marks are cleared (the clear_costmaps recovery) and, after ~max_recoveries such
failures in a row, the goal is aborted.
What kame's move_base does not have yet: a rolling local costmap (the global one serves both),
rotate_recovery, footprint polygons (a round robot of robot_radius).
The algorithms are kame.nav.costmap, kame.nav.planner and kame.nav.local_planner.
"""

from __future__ import annotations

import math
import sys
import threading
from collections.abc import Sequence
from typing import Any

import numpy as np

from kame.client import clock, core, process, services, topics
from kame.client import log as _log
from kame.client.action.simple_action_server import SimpleActionServer
from kame.nav.amcl_node import yaw_of
from kame.nav.costmap import NO_INFORMATION, Costmap, CostmapParams
from kame.nav.local_planner import LocalPlannerParams, compute_velocity, rotate_toward
from kame.nav.planner import make_plan
from kame.net.signal_wake import SignalSafeEvent
from kame.tf import errors as tf_errors
from kame.tf_ros.buffer import Buffer
from kame.tf_ros.node_io import TransformListener


def _param(name: str, default: Any) -> Any:
    return process.get_param("~" + name, default)


def costmap_params() -> CostmapParams:
    ns = "global_costmap/"
    radius = float(_param(ns + "robot_radius", CostmapParams.robot_radius))
    inflation = _param(ns + "inflation_layer/inflation_radius", _param(ns + "inflation_radius", 0.55))
    scaling = _param(ns + "inflation_layer/cost_scaling_factor", _param(ns + "cost_scaling_factor", 10.0))
    return CostmapParams(robot_radius=radius, inflation_radius=float(inflation), cost_scaling_factor=float(scaling),
                         obstacle_range=float(_param(ns + "obstacle_layer/scan/obstacle_range",
                                                     _param(ns + "obstacle_range", 2.5))),
                         raytrace_range=float(_param(ns + "obstacle_layer/scan/raytrace_range",
                                                     _param(ns + "raytrace_range", 3.0))))


def planner_params() -> LocalPlannerParams:
    values: dict[str, Any] = {}
    for name, spec in LocalPlannerParams.__dataclass_fields__.items():
        kind = int if spec.type in ("int", int) else float
        values[name] = kind(_param("DWAPlannerROS/" + name, _param(name, spec.default)))
    return LocalPlannerParams(**values)


class MoveBase:
    def __init__(self) -> None:
        self.costmap_params = costmap_params()
        self.planner = planner_params()
        self.global_frame = str(_param("global_costmap/global_frame", "map"))
        self.base_frame = str(_param("global_costmap/robot_base_frame", "base_footprint"))
        self.max_recoveries = int(_param("max_recoveries", 2))
        self.lock = threading.Lock()
        self.costmap: Costmap | None = None
        self.map_ready = SignalSafeEvent()  # the main thread waits on it
        self.velocity = (0.0, 0.0)
        node = core.get_node()
        assert node is not None
        self.buffer = Buffer(warn=lambda text: _log.emit(_log.WARN, text, ()))
        self.listener = TransformListener(node, self.buffer, now=lambda: clock.get_rostime().to_nsec())
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import OccupancyGrid, Path
        self.cmd_vel = topics.Publisher("cmd_vel", Twist, queue_size=1)
        self.costmap_pub = topics.Publisher("~global_costmap/costmap", OccupancyGrid, queue_size=1, latch=True)
        self.plan_pub = topics.Publisher("~NavfnROS/plan", Path, queue_size=1)

    # ---------------------------------------------------------------- inputs

    def on_map(self, msg: Any) -> None:
        info = msg.info
        data = msg.data
        cells = np.frombuffer(data, dtype=np.int8) if isinstance(data, bytes) else np.asarray(data, np.int16)
        costmap = Costmap(cells.reshape(info.height, info.width), info.resolution,
                          (info.origin.position.x, info.origin.position.y), self.costmap_params)
        with self.lock:
            self.costmap = costmap
        self._publish_costmap(msg)
        self.map_ready.set()

    def on_scan(self, scan: Any) -> None:
        try:
            found = self.buffer.lookup_transform(self.global_frame, scan.header.frame_id, scan.header.stamp,
                                                 clock.Duration(0.2))
        except tf_errors.TransformException:
            return
        x, y = found.transform.translation.x, found.transform.translation.y
        yaw = yaw_of(found.transform.rotation)
        ranges = np.asarray(scan.ranges, dtype=float)
        angles = yaw + scan.angle_min + scan.angle_increment * np.arange(len(ranges))
        seen = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges < scan.range_max)
        points = np.column_stack((x + ranges[seen] * np.cos(angles[seen]), y + ranges[seen] * np.sin(angles[seen])))
        with self.lock:
            if self.costmap is not None:
                self.costmap.update_from_scan((x, y), points)

    def robot_pose(self) -> tuple[float, float, float] | None:
        try:
            found = self.buffer.lookup_transform(self.global_frame, self.base_frame, 0, clock.Duration(0.5))
        except tf_errors.TransformException as exc:
            _log.emit_throttle(5.0, _log.WARN, "Unable to get the robot's pose: %s", (exc,))
            return None
        return found.transform.translation.x, found.transform.translation.y, yaw_of(found.transform.rotation)

    # ---------------------------------------------------------------- planning and driving

    def plan(self, start: tuple[float, float], goal: tuple[float, float]) -> list[tuple[float, float]] | None:
        with self.lock:
            if self.costmap is None:
                return None
            return make_plan(self.costmap, start, goal)

    def make_plan_service(self, request: Any) -> Any:
        from geometry_msgs.msg import PoseStamped
        from nav_msgs.srv import GetPlanResponse
        start = request.start.pose.position
        goal = request.goal.pose.position
        path = self.plan((start.x, start.y), (goal.x, goal.y))
        response = GetPlanResponse()
        response.plan.header.frame_id = self.global_frame
        for px, py in path or []:
            pose = PoseStamped()
            pose.header.frame_id = self.global_frame
            pose.pose.position.x, pose.pose.position.y = px, py
            pose.pose.orientation.w = 1.0
            response.plan.poses.append(pose)
        return response

    def send(self, linear: float, angular: float) -> None:
        from geometry_msgs.msg import Twist
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        self.velocity = (linear, angular)
        self.cmd_vel.publish(twist)

    def execute(self, server: SimpleActionServer, goal: Any) -> None:
        target = goal.target_pose
        frame = target.header.frame_id.lstrip("/")
        if frame and frame != self.global_frame:
            server.set_aborted(text=f"goals must be given in the global frame [{self.global_frame}], not [{frame}]")
            return
        gx, gy, gyaw = target.pose.position.x, target.pose.position.y, yaw_of(target.pose.orientation)
        cycle = 1.0 / self.planner.controller_frequency
        path: list[tuple[float, float]] | None = None
        failures = 0
        plan_failures = 0
        tick = 0
        while not core.is_shutdown():
            if server.is_preempt_requested():
                self.send(0.0, 0.0)
                server.set_preempted()
                return
            pose = self.robot_pose()
            if pose is not None:
                if math.hypot(pose[0] - gx, pose[1] - gy) <= self.planner.xy_goal_tolerance:
                    turn = rotate_toward(pose[2], gyaw, self.planner)
                    if abs(math.remainder(gyaw - pose[2], 2 * math.pi)) <= self.planner.yaw_goal_tolerance:
                        self.send(0.0, 0.0)
                        server.set_succeeded(text="Goal reached.")
                        return
                    self.send(0.0, turn)
                else:
                    if path is None or tick % round(self.planner.controller_frequency) == 0:
                        path = self.plan(pose[:2], (gx, gy))
                        if path is None:
                            self.send(0.0, 0.0)
                            plan_failures += 1
                            if plan_failures > self.max_recoveries:
                                server.set_aborted(text="Failed to find a valid plan. Even after executing "
                                                        "recovery behaviors.")
                                return
                            # the clear_costmaps recovery: what the laser marked may be what blocks
                            with self.lock:
                                assert self.costmap is not None
                                self.costmap.clear_obstacles()
                            tick += 1
                            core.wait_for_shutdown(cycle)
                            continue
                        plan_failures = 0
                        self._publish_plan(path)
                    with self.lock:
                        assert self.costmap is not None
                        command = compute_velocity(self.costmap, pose, self.velocity, path, self.planner)
                    if command is None:
                        failures += 1
                        if failures > self.max_recoveries:
                            self.send(0.0, 0.0)
                            server.set_aborted(text="Failed to find a valid control. Even after executing "
                                                    "recovery behaviors.")
                            return
                        with self.lock:
                            assert self.costmap is not None
                            self.costmap.clear_obstacles()
                        path = None
                        command = (0.0, 0.0)
                    else:
                        failures = 0
                    self.send(*command)
            tick += 1
            core.wait_for_shutdown(cycle)

    # ---------------------------------------------------------------- outputs

    def _publish_costmap(self, map_msg: Any) -> None:
        from nav_msgs.msg import OccupancyGrid
        with self.lock:
            assert self.costmap is not None
            costs = self.costmap.costs.astype(np.int16)
        grid = OccupancyGrid()
        grid.header.frame_id = self.global_frame
        grid.info = map_msg.info
        shown = np.where(costs == NO_INFORMATION, -1, np.round(costs * 100.0 / 254.0)).astype(np.int8)
        grid.data = shown.reshape(-1).tolist()
        self.costmap_pub.publish(grid)

    def _publish_plan(self, path: list[tuple[float, float]]) -> None:
        from geometry_msgs.msg import PoseStamped
        from nav_msgs.msg import Path
        msg = Path()
        msg.header.frame_id = self.global_frame
        for px, py in path:
            pose = PoseStamped()
            pose.header.frame_id = self.global_frame
            pose.pose.position.x, pose.pose.position.y = px, py
            pose.pose.orientation.w = 1.0
            msg.poses.append(pose)
        self.plan_pub.publish(msg)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    _log.use_roscpp_console()
    process.init_node("move_base", argv=argv)
    from geometry_msgs.msg import PoseStamped
    from move_base_msgs.msg import MoveBaseAction, MoveBaseActionGoal
    from nav_msgs.msg import OccupancyGrid
    from nav_msgs.srv import GetPlan
    from sensor_msgs.msg import LaserScan

    move_base = MoveBase()
    topics.Subscriber("map", OccupancyGrid, move_base.on_map, queue_size=1)
    scan_topic = str(_param("global_costmap/obstacle_layer/scan/topic", "scan"))
    topics.Subscriber(scan_topic, LaserScan, move_base.on_scan, queue_size=1)
    # as move_base's global costmap, take goals only once the static map is in
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
    process.spin()
    return 0
