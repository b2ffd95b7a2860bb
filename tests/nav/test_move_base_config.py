"""move_base's parameters as turtlebot_navigation lays them out (kame.nav.config): names,
defaults, footprints and the recovery behaviours' order."""

from __future__ import annotations

import math
from typing import Any

import pytest

from kame.nav.config import (
    CLEAR,
    ROTATE,
    ConfigError,
    costmap_config,
    inscribed_radius,
    move_base_config,
    parse_footprint,
)
from tests.nav.worlds import turtlebot_move_base_params


def getter(values: dict[str, Any]) -> Any:
    return lambda name, default: values.get(name, default)


def test_turtlebot_navigation_files() -> None:
    get = turtlebot_move_base_params()
    local = costmap_config(get, "local_costmap")
    assert (local.global_frame, local.robot_base_frame, local.rolling_window) == ("odom", "base_footprint", True)
    assert (local.width, local.height, local.update_frequency, local.publish_frequency) == (4.0, 4.0, 5.0, 2.0)
    assert [(s.name, s.topic, s.data_type) for s in local.sources] == [
        ("scan", "scan", "LaserScan"), ("bump", "mobile_base/sensors/bumper_pointcloud", "PointCloud2")]
    assert local.sources[1].clearing is False
    glob = costmap_config(get, "global_costmap")
    assert glob.global_frame == "map" and not glob.rolling_window and glob.static_map
    assert glob.layers.track_unknown_space and not local.layers.track_unknown_space
    assert (glob.layers.inflation_radius, glob.layers.cost_scaling_factor) == (0.5, 5.0)
    assert (glob.layers.obstacle_range, glob.layers.raytrace_range) == (2.5, 3.0)
    config = move_base_config(get, glob.circumscribed_radius)
    assert (config.controller_frequency, config.planner_frequency) == (5.0, 1.0)
    assert (config.controller_patience, config.planner_patience, config.oscillation_timeout) == (3.0, 5.0, 10.0)
    assert config.local_planner_name == "DWAPlannerROS" and config.global_planner_name == "NavfnROS"
    assert [(r.name, r.kind, r.reset_distance) for r in config.recoveries] == [
        ("conservative_reset", CLEAR, 3.0), ("rotate_recovery", ROTATE, 3.0),
        ("aggressive_reset", CLEAR, pytest.approx(0.8)), ("rotate_recovery", ROTATE, 3.0)]


def test_move_base_defaults_and_old_layout() -> None:
    config = move_base_config(getter({"clearing_rotation_allowed": False}), 0.46)
    assert (config.controller_frequency, config.planner_frequency, config.controller_patience) == (20.0, 0.0, 15.0)
    assert [r.name for r in config.recoveries] == ["conservative_reset", "aggressive_reset"]
    assert config.local_planner_name == "TrajectoryPlannerROS"
    # costmap_2d's pre-Hydro names, straight in the costmap's namespace
    old = costmap_config(getter({"global_costmap/inflation_radius": 0.3, "global_costmap/robot_radius": 0.18}),
                         "global_costmap")
    assert (old.layers.inflation_radius, old.layers.robot_radius, old.global_frame) == (0.3, 0.18, "map")


def test_recovery_behaviors_as_given() -> None:
    config = move_base_config(getter({
        "recovery_behaviors": [{"name": "reset", "type": CLEAR}, {"name": "spin", "type": ROTATE}],
        "reset/reset_distance": 1.5}), 0.2)
    assert [(r.name, r.kind, r.reset_distance) for r in config.recoveries] == [
        ("reset", CLEAR, 1.5), ("spin", ROTATE, 3.0)]
    with pytest.raises(ConfigError, match="Failed to create the move_slow_and_clear"):
        move_base_config(getter({"recovery_behaviors": [{"name": "x", "type": "move_slow_and_clear"}]}), 0.2)
    with pytest.raises(ConfigError, match="must be a list"):
        move_base_config(getter({"recovery_behaviors": "rotate"}), 0.2)


def test_footprints() -> None:
    square = parse_footprint("[[-0.2, -0.2], [-0.2, 0.2], [0.3, 0.2], [0.3, -0.2]]")
    assert inscribed_radius(square) == pytest.approx(0.2)
    config = costmap_config(getter({"local_costmap/footprint": [list(p) for p in square]}), "local_costmap")
    assert config.layers.robot_radius == pytest.approx(0.2)  # inflation's inscribed radius
    assert config.circumscribed_radius == pytest.approx(math.hypot(0.3, 0.2))
    assert parse_footprint([]) == ()
    for bad in ("[[0, 0], [1, 1]]", "not a list", [[0, "a"], [1, 1], [2, 2]]):
        with pytest.raises(ConfigError):
            parse_footprint(bad)
