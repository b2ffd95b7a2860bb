"""navfn's global plan, pure: the cheapest 8-connected path over a costmap, by Dijkstra
(scipy.sparse.csgraph) on navfn's cell costs: COST_NEUTRAL + COST_FACTOR * cost for a cell
below the inscribed cost; inscribed, lethal (and, unless allow_unknown, unknown) cells are walls.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from kame.nav.costmap import INSCRIBED_INFLATED_OBSTACLE, NO_INFORMATION, Costmap

COST_NEUTRAL = 50.0
COST_FACTOR = 0.8
_NEIGHBOURS = ((0, 1, 1.0), (1, 0, 1.0), (1, 1, math.sqrt(2)), (1, -1, math.sqrt(2)))


def passable(costs: np.ndarray, allow_unknown: bool) -> np.ndarray:
    open_cells = costs < INSCRIBED_INFLATED_OBSTACLE
    if allow_unknown:
        open_cells |= costs == NO_INFORMATION
    return open_cells


def make_plan(costmap: Costmap, start: tuple[float, float], goal: tuple[float, float],
              allow_unknown: bool = True) -> list[tuple[float, float]] | None:
    """The path's cell centres from start to goal (both in the map frame), or None when the goal
    cannot be reached (off the map, in an obstacle, or walled off)."""
    start_cell, goal_cell = costmap.cell_of(*start), costmap.cell_of(*goal)
    if start_cell is None or goal_cell is None:
        return None
    costs = costmap.costs
    open_cells = passable(costs, allow_unknown)
    if not open_cells[goal_cell]:
        return None
    open_cells[start_cell] = True  # the robot may stand in its own inflation; it has to leave it
    rows, columns = costs.shape
    step_cost = COST_NEUTRAL + COST_FACTOR * np.where(costs == NO_INFORMATION, 0, costs).astype(float)
    index = np.arange(rows * columns).reshape(rows, columns)
    sources, targets, weights = [], [], []
    for dr, dc, length in _NEIGHBOURS:
        a = (slice(max(-dr, 0), rows - max(dr, 0)), slice(max(-dc, 0), columns - max(dc, 0)))
        b = (slice(max(dr, 0), rows - max(-dr, 0)), slice(max(dc, 0), columns - max(-dc, 0)))  # a's neighbours
        both = open_cells[a] & open_cells[b]
        for here, there in ((a, b), (b, a)):
            sources.append(index[here][both])
            targets.append(index[there][both])
            weights.append(length * step_cost[there][both])
    size = rows * columns
    graph = coo_matrix((np.concatenate(weights), (np.concatenate(sources), np.concatenate(targets))),
                       shape=(size, size)).tocsr()
    start_index, goal_index = index[start_cell], index[goal_cell]
    distances, predecessors = dijkstra(graph, indices=int(start_index), return_predecessors=True)
    if not np.isfinite(distances[goal_index]):
        return None
    path = [int(goal_index)]
    while path[-1] != start_index:
        path.append(int(predecessors[path[-1]]))
    path.reverse()
    return [costmap.centre_of(i // columns, i % columns) for i in path]
