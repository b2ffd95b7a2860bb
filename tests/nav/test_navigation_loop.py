"""The navigation loop without ROS: the office world's robot steered by the costmap, navfn's plan
and the DWA local planner, configured by turtlebot_navigation's parameter files, reaches goals
across the office, around a box it only meets on the way."""

from __future__ import annotations

import math

import numpy as np

from kame.nav.config import costmap_config, local_planner_params
from kame.nav.costmap import Costmap
from kame.nav.local_planner import LocalPlannerParams, compute_velocity
from kame.nav.planner import make_plan
from kame.stage.world import LaserModel, OdometryModel, Walls, World
from tests.nav.worlds import load_world_map, turtlebot_move_base_params


def navigate(world: World, costmap: Costmap, goal: tuple[float, float], params: LocalPlannerParams,
             seconds: float = 90.0) -> bool:
    cycle = 1.0 / params.controller_frequency
    laser = world.laser
    path: list[tuple[float, float]] | None = None
    for tick in range(round(seconds / cycle)):
        robot = world.robot("bot")
        assert not robot.stalled, f"bumped into something at {robot.pose}"
        pose = (robot.pose.x, robot.pose.y, robot.pose.theta)
        if math.dist(pose[:2], goal) < params.xy_goal_tolerance:
            return True
        ranges = world.scans(["bot"])["bot"]
        seen = np.isfinite(ranges)
        angles = pose[2] + laser.angles()[seen]
        points = np.column_stack((pose[0] + ranges[seen] * np.cos(angles), pose[1] + ranges[seen] * np.sin(angles)))
        costmap.update_from_scan(pose[:2], points)
        if path is None or tick % 5 == 0:  # planner_frequency: 1 Hz
            path = make_plan(costmap, pose[:2], goal)
            assert path is not None, f"no plan from {pose} to {goal}"
        command = compute_velocity(costmap, pose, (robot.linear, robot.angular), path, params)
        if command is None:  # recovery: clear what the sensors marked, then plan again
            costmap.clear_obstacles()
            path = None
            command = (0.0, 0.0)
        world.command("bot", *command)
        for _ in range(4):
            world.step(cycle / 4)
    return False


def test_goals_across_the_office_around_a_box() -> None:
    grid = load_world_map("office")
    world = World(Walls(grid), laser=LaserModel(noise=0.01), odometry=OdometryModel(0.0, 0.0), seed=0)
    world.spawn("bot", 0.0, 0.0, 0.0)
    world.spawn("box", 1.2, 0.1, 0.0)  # in the corridor, not on the map: only the laser sees it
    get = turtlebot_move_base_params()
    params = local_planner_params(get, "DWAPlannerROS", float(get("controller_frequency", 20.0)))
    assert params.max_vel_x == 0.5 and params.sim_time == 1.0 and params.vth_samples == 20
    config = costmap_config(get, "global_costmap")
    assert config.layers.robot_radius == 0.2 and config.layers.inflation_radius == 0.5
    costmap = Costmap(grid.cells, grid.resolution, grid.origin[:2], config.layers)
    box = costmap.cell_of(1.2, 0.1)
    assert box is not None and costmap.costs[box] == 0
    for goal in [(2.0, -3.0), (-6.0, 0.2), (-2.0, 3.0)]:
        assert navigate(world, costmap, goal, params), f"did not reach {goal}: at {world.robot('bot').pose}"
        robot = world.robot("bot").pose
        assert math.dist((robot.x, robot.y), goal) < 0.25
        if goal == (2.0, -3.0):
            rows, columns = np.nonzero(costmap.obstacles)
            marked = [costmap.centre_of(r, c) for r, c in zip(rows.tolist(), columns.tolist(), strict=True)]
            assert any(math.dist(m, (1.2, 0.1)) < 0.25 for m in marked)  # the box, seen on the way, went around
