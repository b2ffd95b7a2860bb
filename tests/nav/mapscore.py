"""How well a built map matches the world's, for the SLAM tests (on the world model and live).

The map's frame is where the robot starts, as gmapping's, and the simulated robot starts at the
world's origin facing along x, so the built map and the world's map share their frame. The
metric, over the world's cells (each looked up at its centre in the built map):
- agreement: of the cells the built map knows (free or occupied), the share whose state is the
  world's (a wall cell being occupied);
- walls within 2 cells, both ways: the share of the built map's occupied cells within 2 cells of
  a wall of the world (none drawn where there is no wall), and the share of the world's wall
  cells that the built map knows that have an occupied cell within 2 cells (the walls it saw are
  drawn, not left free).
Agreement alone is weak (most known cells are free), hence the two wall figures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from kame.nav.slam import MapView
from kame.stage.mapfile import Grid

# the thresholds the SLAM tests hold a map to
AGREEMENT, DRAWN_NEAR_WALLS, WALLS_DRAWN = 0.9, 0.8, 0.85


@dataclass(frozen=True)
class MapScore:
    known: int
    agreement: float
    drawn_near_walls: float
    walls_drawn: float


def score(view: MapView, truth_grid: Grid) -> MapScore:
    truth = np.asarray(truth_grid.cells) >= 65
    rows, columns = truth.shape
    x = truth_grid.origin[0] + (np.arange(columns) + 0.5) * truth_grid.resolution
    y = truth_grid.origin[1] + (np.arange(rows) + 0.5) * truth_grid.resolution
    column = np.floor((x - view.origin[0]) / view.resolution).astype(np.int64)
    row = np.floor((y - view.origin[1]) / view.resolution).astype(np.int64)
    built = np.full(truth.shape, -1, dtype=np.int8)
    in_columns = (column >= 0) & (column < view.cells.shape[1])
    in_rows = (row >= 0) & (row < view.cells.shape[0])
    built[np.ix_(in_rows, in_columns)] = view.cells[np.ix_(row[in_rows], column[in_columns])]
    known, occupied = built != -1, built == 100
    to_wall = ndimage.distance_transform_edt(~truth)
    to_drawn = ndimage.distance_transform_edt(~occupied)
    return MapScore(int(known.sum()), float((occupied == truth)[known].mean()),
                    float((to_wall[occupied] <= 2).mean()), float((to_drawn[truth & known] <= 2).mean()))
