"""costmap_2d's layers and navfn's plan on the office map, without ROS."""

from __future__ import annotations

import itertools
import math

import numpy as np

from kame.nav.costmap import (
    FREE_SPACE,
    INSCRIBED_INFLATED_OBSTACLE,
    LETHAL_OBSTACLE,
    NO_INFORMATION,
    Costmap,
    CostmapParams,
)
from kame.nav.planner import make_plan
from tests.nav.worlds import load_world_map


def office_costmap(**params: object) -> Costmap:
    grid = load_world_map("office")
    return Costmap(grid.cells, grid.resolution, grid.origin[:2], CostmapParams(**params))  # type: ignore[arg-type]


def test_inflation_decays_from_the_walls() -> None:
    cells = np.zeros((40, 40), dtype=np.int8)
    cells[:, 20] = 100
    costmap = Costmap(cells, 0.05, (0.0, 0.0), CostmapParams(robot_radius=0.2, inflation_radius=0.55))
    row = costmap.costs[10]
    assert row[20] == LETHAL_OBSTACLE
    assert row[17] == row[16] == INSCRIBED_INFLATED_OBSTACLE  # 0.15 and 0.2 m from the wall
    assert LETHAL_OBSTACLE > row[15] > row[14] > row[12] > 0  # 0.25 m onwards: decaying
    assert row[15] == math.floor(252 * math.exp(-10 * (0.25 - 0.2)))
    assert row[9] > 0 and row[8] == FREE_SPACE  # 0.55 m is inflated, 0.6 m is not


def test_unknown_space_is_tracked_when_asked() -> None:
    cells = np.full((10, 10), -1, dtype=np.int8)
    assert (Costmap(cells, 0.05, (0, 0), CostmapParams()).costs == FREE_SPACE).all()
    assert (Costmap(cells, 0.05, (0, 0), CostmapParams(track_unknown_space=True)).costs == NO_INFORMATION).all()


def test_a_plan_through_the_office_goes_through_the_door() -> None:
    costmap = office_costmap()
    path = make_plan(costmap, (0.0, 0.0), (2.0, -3.0))
    assert path is not None
    assert math.dist(path[0], (0.0, 0.0)) < 0.05 and math.dist(path[-1], (2.0, -3.0)) < 0.05
    crossing = [x for x, y in path if -1.05 <= y <= -0.95]  # the south wall, with its door at 1.5..2.5
    assert crossing and all(1.5 < x < 2.5 for x in crossing)
    cells = [costmap.cell_of(x, y) for x, y in path]
    assert all(costmap.costs[c] < INSCRIBED_INFLATED_OBSTACLE for c in cells if c is not None)
    steps = [math.dist(a, b) for a, b in itertools.pairwise(path)]
    assert max(steps) < 0.05 * math.sqrt(2) + 1e-9  # neighbouring cells


def test_a_goal_in_a_wall_or_walled_off_cannot_be_planned() -> None:
    costmap = office_costmap()
    assert make_plan(costmap, (0.0, 0.0), (0.0, 0.98)) is None  # in the corridor's north wall
    assert make_plan(costmap, (0.0, 0.0), (30.0, 0.0)) is None  # off the map
    door = np.column_stack((np.linspace(1.5, 2.5, 41), np.full(41, -1.0)))
    costmap.update_from_scan((2.0, 0.0), door)  # a scan sees the south room's door closed
    assert make_plan(costmap, (0.0, 0.0), (2.0, -3.0)) is None
    costmap.clear_obstacles()
    assert make_plan(costmap, (0.0, 0.0), (2.0, -3.0)) is not None


def test_the_obstacle_layer_marks_and_clears() -> None:
    costmap = office_costmap()
    box = costmap.cell_of(1.0, 0.0)
    assert box is not None
    costmap.update_from_scan((0.0, 0.0), np.array([[1.0, 0.0]]))
    assert costmap.costs[box] == LETHAL_OBSTACLE
    path = make_plan(costmap, (0.0, 0.0), (2.0, 0.0))
    assert path is not None and min(math.dist(p, (1.0, 0.0)) for p in path) > costmap.params.robot_radius
    costmap.update_from_scan((0.0, 0.0), np.array([[2.0, 0.0]]))  # the box is gone: the ray clears it
    assert costmap.costs[box] == FREE_SPACE
    costmap.update_from_scan((0.0, 0.0), np.array([[2.8, 0.0]]))  # beyond obstacle_range: not marked
    far = costmap.cell_of(2.8, 0.0)
    assert far is not None and costmap.costs[far] == FREE_SPACE
