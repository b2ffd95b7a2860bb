"""A DWA local planner, pure: base_local_planner's dynamic window search on numpy.

Each control cycle samples (v, w) pairs reachable within one cycle under the acceleration
limits (vx_samples x vth_samples), drops those slower than min_trans_vel and min_rot_vel
(standing still is no trajectory, as in dwa_local_planner), rolls each forward for sim_time at constant speed, drops
those whose footprint centre enters an inscribed or lethal cell, and scores the rest as
base_local_planner does: path_distance_bias * (distance from the trajectory's end to the plan)
+ goal_distance_bias * (distance from the end to the local goal, the plan's last point within
the local window) + occdist_scale * (the highest cost crossed), the two distances also taken
from a point forward_point_distance ahead of the end (dwa_local_planner's alignment and
goal-front costs) until the goal is nearer than twice that; the cheapest wins.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kame.nav.costmap import INSCRIBED_INFLATED_OBSTACLE, Costmap


@dataclass(frozen=True)
class LocalPlannerParams:
    """dwa_local_planner's parameters, with the TurtleBot's dwa_local_planner_params.yaml values."""

    max_vel_x: float = 0.5
    min_vel_x: float = 0.0
    max_rot_vel: float = 1.5
    acc_lim_x: float = 1.0
    acc_lim_theta: float = 2.0
    sim_time: float = 1.7
    sim_granularity: float = 0.05
    vx_samples: int = 6
    vth_samples: int = 20
    path_distance_bias: float = 32.0
    goal_distance_bias: float = 24.0
    occdist_scale: float = 0.02
    min_trans_vel: float = 0.1  # a trajectory slower than both of these is no trajectory (it stands still)
    min_rot_vel: float = 0.4
    forward_point_distance: float = 0.325  # the point ahead of each end that is scored too (turns toward the path)
    xy_goal_tolerance: float = 0.15
    yaw_goal_tolerance: float = 0.3
    local_window: float = 2.0  # metres of plan ahead that the local goal may lie in
    controller_frequency: float = 5.0


def local_goal(path: np.ndarray, position: tuple[float, float], window: float) -> tuple[int, int]:
    """(index of the plan point nearest the robot, index of the last point within `window`)."""
    offsets = np.hypot(path[:, 0] - position[0], path[:, 1] - position[1])
    nearest = int(np.argmin(offsets))
    ahead = np.nonzero(offsets[nearest:] <= window)[0]
    last = nearest + int(ahead.max()) if len(ahead) else nearest
    return nearest, last


@dataclass(frozen=True)
class Trajectory:
    """The chosen command and the (x, y) points it was rolled out to (base_local_planner's local_plan)."""

    linear: float
    angular: float
    points: np.ndarray


def compute_velocity(costmap: Costmap, pose: tuple[float, float, float], velocity: tuple[float, float],
                     path: list[tuple[float, float]], params: LocalPlannerParams) -> tuple[float, float] | None:
    """The (linear, angular) command for this cycle, or None when every sampled trajectory collides."""
    best = choose_trajectory(costmap, pose, velocity, path, params)
    return None if best is None else (best.linear, best.angular)


def choose_trajectory(costmap: Costmap, pose: tuple[float, float, float], velocity: tuple[float, float],
                      path: list[tuple[float, float]], params: LocalPlannerParams) -> Trajectory | None:
    """The cheapest collision-free sampled trajectory, or None when every one collides."""
    plan = np.asarray(path, dtype=float)
    nearest, last = local_goal(plan, (pose[0], pose[1]), params.local_window)
    ahead = plan[nearest:last + 1]
    goal = plan[last]
    cycle = 1.0 / params.controller_frequency
    v_now, w_now = velocity
    linear = np.linspace(max(params.min_vel_x, v_now - params.acc_lim_x * cycle),
                         min(params.max_vel_x, v_now + params.acc_lim_x * cycle), params.vx_samples)
    angular = np.linspace(max(-params.max_rot_vel, w_now - params.acc_lim_theta * cycle),
                          min(params.max_rot_vel, w_now + params.acc_lim_theta * cycle), params.vth_samples)
    v, w = (grid.reshape(-1) for grid in np.meshgrid(linear, angular))
    steps = max(math.ceil(params.sim_time / params.sim_granularity), 1)
    t = np.arange(1, steps + 1) * params.sim_granularity
    theta = pose[2] + w[:, None] * t[None, :]
    turning = np.abs(w) > 1e-6
    safe_w = np.where(turning, w, 1.0)[:, None]
    x = np.where(turning[:, None], pose[0] + v[:, None] / safe_w * (np.sin(theta) - math.sin(pose[2])),
                 pose[0] + v[:, None] * t[None, :] * math.cos(pose[2]))
    y = np.where(turning[:, None], pose[1] - v[:, None] / safe_w * (np.cos(theta) - math.cos(pose[2])),
                 pose[1] + v[:, None] * t[None, :] * math.sin(pose[2]))
    rows, columns = costmap.shape
    column = np.floor((x - costmap.origin[0]) / costmap.resolution).astype(np.int64)
    row = np.floor((y - costmap.origin[1]) / costmap.resolution).astype(np.int64)
    inside = (row >= 0) & (row < rows) & (column >= 0) & (column < columns)
    costs = np.full(x.shape, 255, dtype=np.int64)
    costs[inside] = costmap.costs[row[inside], column[inside]]
    moving = (np.abs(v) >= params.min_trans_vel) | (np.abs(w) >= params.min_rot_vel)
    valid = (costs < INSCRIBED_INFLATED_OBSTACLE).all(axis=1) & moving
    if not valid.any():
        return None
    end_x, end_y = x[:, -1], y[:, -1]

    def to_path(px: np.ndarray, py: np.ndarray) -> np.ndarray:
        nearest: np.ndarray = np.min(np.hypot(px[:, None] - ahead[None, :, 0], py[:, None] - ahead[None, :, 1]),
                                     axis=1)
        return nearest

    path_distance = to_path(end_x, end_y)
    goal_distance = np.hypot(end_x - goal[0], end_y - goal[1])
    if math.hypot(pose[0] - plan[-1][0], pose[1] - plan[-1][1]) >= 2 * params.forward_point_distance:
        # dwa_local_planner's alignment and goal-front costs: a point ahead of the end, so that
        # facing along the plan scores better than standing still facing away from it. Near the
        # goal they would hold the end a forward_point_distance short of it, so they stop there.
        front_x = end_x + params.forward_point_distance * np.cos(theta[:, -1])
        front_y = end_y + params.forward_point_distance * np.sin(theta[:, -1])
        path_distance = path_distance + to_path(front_x, front_y)
        goal_distance = goal_distance + np.hypot(front_x - goal[0], front_y - goal[1])
    score = (params.path_distance_bias * path_distance + params.goal_distance_bias * goal_distance) \
        / costmap.resolution + params.occdist_scale * costs.max(axis=1)
    score[~valid] = np.inf
    best = int(np.argmin(score))
    return Trajectory(float(v[best]), float(w[best]), np.column_stack((x[best], y[best])))


def rotate_toward(yaw: float, goal_yaw: float, params: LocalPlannerParams) -> float:
    """At the goal's position: turn on the spot toward its heading (proportional, capped)."""
    error = math.remainder(goal_yaw - yaw, 2 * math.pi)
    return max(-params.max_rot_vel, min(params.max_rot_vel, 2.0 * error))
