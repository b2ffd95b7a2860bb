"""costmap_2d's layered grid, pure: a static layer from a map, an obstacle layer marked and
cleared by laser points, and the inflation layer, combined as costmap_2d combines them.

Costs are costmap_2d's: 0 free, 253 inscribed (the robot's centre there means a collision),
254 lethal, 255 unknown; around lethal cells the inflation layer decays as
252 * exp(-cost_scaling_factor * (distance - inscribed_radius)) out to inflation_radius.
Distances come from scipy's exact Euclidean distance transform, not a hand-written wavefront.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

FREE_SPACE = 0
INSCRIBED_INFLATED_OBSTACLE = 253
LETHAL_OBSTACLE = 254
NO_INFORMATION = 255


@dataclass(frozen=True)
class CostmapParams:
    """The parameters of costmap_common_params.yaml that shape the grid, with costmap_2d's defaults."""

    robot_radius: float = 0.46 * 0.5  # inscribed radius of a round robot (costmap_2d: robot_radius)
    inflation_radius: float = 0.55
    cost_scaling_factor: float = 10.0
    lethal_cost_threshold: int = 100  # static layer: map values at or above this are lethal
    track_unknown_space: bool = False
    obstacle_range: float = 2.5  # marking: points nearer than this
    raytrace_range: float = 3.0  # clearing: rays out to this


class Costmap:
    """One layered costmap over a map's cells (row 0 at the origin's y)."""

    def __init__(self, map_cells: np.ndarray, resolution: float, origin: tuple[float, float],
                 params: CostmapParams) -> None:
        cells = np.asarray(map_cells, dtype=np.int16)
        self.params = params
        self.resolution = float(resolution)
        self.origin = (float(origin[0]), float(origin[1]))
        self.static = np.full(cells.shape, FREE_SPACE, dtype=np.uint8)
        self.static[cells >= params.lethal_cost_threshold] = LETHAL_OBSTACLE
        if params.track_unknown_space:
            self.static[cells < 0] = NO_INFORMATION
        self.obstacles = np.zeros(cells.shape, dtype=bool)  # the obstacle layer's marks
        self.cleared = np.zeros(cells.shape, dtype=bool)
        self.costs = self._combine()

    @property
    def shape(self) -> tuple[int, int]:
        rows, columns = np.shape(self.static)
        return int(rows), int(columns)

    def cell_of(self, x: float, y: float) -> tuple[int, int] | None:
        """(row, column) of a point, None off the map (and for a coordinate that is NaN or inf)."""
        if not (math.isfinite(x) and math.isfinite(y)):
            return None
        column = math.floor((x - self.origin[0]) / self.resolution)
        row = math.floor((y - self.origin[1]) / self.resolution)
        rows, columns = self.shape
        return (row, column) if 0 <= row < rows and 0 <= column < columns else None

    def bounds(self) -> tuple[float, float, float, float]:
        """(x min, y min, x max, y max): the map's area in its frame."""
        rows, columns = self.shape
        x, y = self.origin
        return x, y, x + columns * self.resolution, y + rows * self.resolution

    def centre_of(self, row: int, column: int) -> tuple[float, float]:
        return (self.origin[0] + (column + 0.5) * self.resolution, self.origin[1] + (row + 0.5) * self.resolution)

    # ---------------------------------------------------------------- the obstacle layer

    def update_from_scan(self, sensor: tuple[float, float], points: np.ndarray,
                         marking: bool = True, clearing: bool = True) -> None:
        """Clear along each ray from the sensor to its end point (within raytrace_range), then mark
        the end points nearer than obstacle_range; points are (x, y) rows in the map frame."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        offsets = points - np.asarray(sensor)
        lengths = np.hypot(offsets[:, 0], offsets[:, 1])
        rows, columns = self.shape
        if clearing and len(points):
            reach = np.minimum(lengths, self.params.raytrace_range)
            steps = max(math.ceil(float(reach.max()) / (self.resolution / 2)), 1)
            fraction = np.linspace(0.0, 1.0, steps + 1)[:-1]  # stop short of the end cell
            scale = np.where(lengths > 0, reach / np.maximum(lengths, 1e-12), 0.0)
            xs = sensor[0] + offsets[:, 0:1] * scale[:, None] * fraction[None, :]
            ys = sensor[1] + offsets[:, 1:2] * scale[:, None] * fraction[None, :]
            ray_columns = np.floor((xs - self.origin[0]) / self.resolution).astype(np.int64)
            ray_rows = np.floor((ys - self.origin[1]) / self.resolution).astype(np.int64)
            inside = (ray_rows >= 0) & (ray_rows < rows) & (ray_columns >= 0) & (ray_columns < columns)
            self.obstacles[ray_rows[inside], ray_columns[inside]] = False
            self.cleared[ray_rows[inside], ray_columns[inside]] = True
        near = points[lengths < self.params.obstacle_range] if marking else points[:0]
        mark_columns = np.floor((near[:, 0] - self.origin[0]) / self.resolution).astype(np.int64)
        mark_rows = np.floor((near[:, 1] - self.origin[1]) / self.resolution).astype(np.int64)
        inside = (mark_rows >= 0) & (mark_rows < rows) & (mark_columns >= 0) & (mark_columns < columns)
        self.obstacles[mark_rows[inside], mark_columns[inside]] = True
        self.costs = self._combine()

    def clear_obstacles(self, keep_around: tuple[float, float] | None = None, keep_size: float = 0.0) -> None:
        """The clear_costmaps service: forget what the sensors marked; given `keep_around`, only
        outside the square of side keep_size centred there (ClearCostmapRecovery's reset_distance)."""
        keep = np.zeros(self.obstacles.shape, dtype=bool)
        if keep_around is not None and keep_size > 0:
            rows, columns = self.shape
            half = keep_size / 2
            c0 = max(math.floor((keep_around[0] - half - self.origin[0]) / self.resolution), 0)
            r0 = max(math.floor((keep_around[1] - half - self.origin[1]) / self.resolution), 0)
            c1 = min(math.ceil((keep_around[0] + half - self.origin[0]) / self.resolution), columns)
            r1 = min(math.ceil((keep_around[1] + half - self.origin[1]) / self.resolution), rows)
            if c0 < c1 and r0 < r1:
                keep[r0:r1, c0:c1] = True
        self.obstacles &= keep
        self.costs = self._combine()

    def recentre(self, centre: tuple[float, float]) -> None:
        """The rolling window: move the grid so `centre` is in its middle (the origin snapped to
        whole cells, as costmap_2d's updateOrigin), keeping the marks that stay inside."""
        rows, columns = self.shape
        shift_c = math.floor((centre[0] - columns * self.resolution / 2 - self.origin[0]) / self.resolution)
        shift_r = math.floor((centre[1] - rows * self.resolution / 2 - self.origin[1]) / self.resolution)
        if shift_c == 0 and shift_r == 0:
            return
        self.origin = (self.origin[0] + shift_c * self.resolution, self.origin[1] + shift_r * self.resolution)
        moved = np.zeros_like(self.obstacles)
        src_r = slice(max(shift_r, 0), rows + min(shift_r, 0))
        src_c = slice(max(shift_c, 0), columns + min(shift_c, 0))
        dst_r = slice(max(-shift_r, 0), rows + min(-shift_r, 0))
        dst_c = slice(max(-shift_c, 0), columns + min(-shift_c, 0))
        if src_r.start < src_r.stop and src_c.start < src_c.stop:
            moved[dst_r, dst_c] = self.obstacles[src_r, src_c]
        self.obstacles = moved
        self.costs = self._combine()

    # ---------------------------------------------------------------- inflation

    def _combine(self) -> np.ndarray:
        lethal = (self.static == LETHAL_OBSTACLE) | self.obstacles
        costs = self.static.copy()
        costs[self.obstacles] = LETHAL_OBSTACLE
        if lethal.any():
            distance = ndimage.distance_transform_edt(~lethal) * self.resolution
            p = self.params
            decay = 252.0 * np.exp(-p.cost_scaling_factor * (distance - p.robot_radius))
            inflated = np.where(distance <= p.robot_radius, INSCRIBED_INFLATED_OBSTACLE,
                                np.where(distance <= p.inflation_radius, np.floor(decay), 0)).astype(np.uint8)
            known = costs != NO_INFORMATION
            costs = np.where(known & ~lethal, np.maximum(costs, inflated), costs).astype(np.uint8)
        combined: np.ndarray = costs
        return combined


def footprint_hits_lethal(costmap: Costmap, pose: tuple[float, float, float],
                          footprint: tuple[tuple[float, float], ...]) -> int | None:
    """The cost of a lethal cell under the footprint's outline at `pose` (costmap_2d's
    footprintCost: edges walked cell by cell), or None when the outline touches none."""
    corners = np.asarray(footprint, dtype=float)
    c, s = math.cos(pose[2]), math.sin(pose[2])
    xs = pose[0] + c * corners[:, 0] - s * corners[:, 1]
    ys = pose[1] + s * corners[:, 0] + c * corners[:, 1]
    ends_x, ends_y = np.roll(xs, -1), np.roll(ys, -1)
    steps = max(math.ceil(float(np.max(np.hypot(ends_x - xs, ends_y - ys))) / (costmap.resolution / 2)), 1)
    t = np.linspace(0.0, 1.0, steps + 1)
    px = (xs[:, None] + (ends_x - xs)[:, None] * t[None, :]).reshape(-1)
    py = (ys[:, None] + (ends_y - ys)[:, None] * t[None, :]).reshape(-1)
    rows, columns = costmap.shape
    column = np.floor((px - costmap.origin[0]) / costmap.resolution).astype(np.int64)
    row = np.floor((py - costmap.origin[1]) / costmap.resolution).astype(np.int64)
    inside = (row >= 0) & (row < rows) & (column >= 0) & (column < columns)
    lethal = costmap.costs[row[inside], column[inside]] == LETHAL_OBSTACLE
    return LETHAL_OBSTACLE if lethal.any() else None

