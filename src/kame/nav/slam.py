"""gmapping's SLAM, pure: a Rao-Blackwellised particle filter whose particles each carry a
trajectory's pose and its own occupancy grid, refined by scan matching (Grisetti, Stachniss and
Burgard's GMapping, as openslam's gridfastslam and ROS's slam_gmapping run it).

Every scan moves each particle by the odometry's motion plus gmapping's motion noise (srr, srt,
str, stt). When the odometry has gone linearUpdate metres or turned angularUpdate radians since
the last processed scan, each particle's pose is refined on its own map, its weight grows by the
scan's log likelihood there (lsigma), the weights are smoothed by ogain, the particles are
resampled when the effective sample size falls under resampleThreshold, and the scan is written
into every particle's map. All particles are matched and written at once with numpy.

Maps are gmapping's counts: per cell how many scans passed through it (visits) and ended in it
(hits); a cell is occupied above occ_thresh hits per visit, free at or below, unknown unvisited.
The likelihood is gmapping's: an end point within kernelSize cells of an occupied cell (one hit
in ten visits: gmapping's fullness threshold) adds -d^2/lsigma, d being the distance to that
cell's centre, one with none near adds gmapping's null likelihood -0.5/lsigma.
The matcher is gmapping's hill climbing (steps of lstep and astep in x, y and heading, halved
`iterations` times, linearOdometryReliability weighing candidates by their distance from the
start), with kame's changes, each there because the TurtleBot's narrow laser (57 degrees) lost
its way without it in the office world's corridor:
- a correlative search first (every pose within 2 lstep and 3 astep, on the walls blurred by
  sigma), so a heading that drifted while the laser faced a bare wall is caught back;
- the score of an end point is the Gaussian exp(-d^2 / (2 sigma^2)) (gmapping's exp(-d^2/sigma)
  is nearly flat within a cell), interpolated between cells so steps smaller than a cell count;
- only beams that pass through seen space just before their end are scored (see _match).
Where gmapping steps through the beam's cells, kame samples each beam every cell; an end point
is taken half a cell beyond the measured range, inside the surface the beam hit rather than
(half the time) in the free cell before it.
The grid grows as scans reach beyond it; `occupancy()` reports at least xmin..xmax, ymin..ymax.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

Pose = tuple[float, float, float]

_FULLNESS = 0.1  # gmapping's ScanMatcher fullness threshold: a cell this often hit is matched on
_NULL_LIKELIHOOD = -0.5  # gmapping's log likelihood of a beam that ends near no occupied cell
_INTO_SURFACE = 0.5  # cells beyond the measured range where the end point is written
_GROW = 64  # cells the grid grows by at once, beyond what a scan needs
_MOVES = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 1.0, 0.0],
                   [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]])  # gmapping's Front, Back, Left, Right, turns
_SEEN_BEFORE = 3  # cells; the matcher scores beams that pass through seen space this far before their end
_COARSE_BEAMS = 120  # beams the correlative search scores
_COARSE_TURNS = 3  # its angular window, in asteps either way
_COARSE_BLUR = 1.0  # its walls' blur, in sigmas
_MAX_ROUNDS = 60  # bounds the hill climb; gmapping's ends on its own after iterations halvings


@dataclass(frozen=True)
class GmappingParams:
    """slam_gmapping's parameters that shape the filter, with gmapping's names and defaults."""

    maxUrange: float = 80.0  # usable range: longer beams only clear
    maxRange: float = 0.0  # beams beyond this are dropped; 0: the scan's range_max
    sigma: float = 0.05  # the matcher's end point spread, metres
    kernelSize: int = 1  # cells around an end point searched for a wall
    lstep: float = 0.05  # the matcher's first linear step, metres
    astep: float = 0.05  # the matcher's first angular step, radians
    iterations: int = 5  # the matcher's step halvings
    lsigma: float = 0.075  # the end point spread of the likelihood
    ogain: float = 3.0  # smoothing of the weights
    lskip: int = 0  # beams skipped between those matched
    minimumScore: float = 0.0  # a match scoring less keeps the odometry's pose
    srr: float = 0.1  # odometry error in translation from translation
    srt: float = 0.2  # in translation from rotation
    str: float = 0.1  # in rotation from translation
    stt: float = 0.2  # in rotation from rotation
    linearUpdate: float = 1.0  # metres driven between processed scans
    angularUpdate: float = 0.5  # radians turned between processed scans
    temporalUpdate: float = -1.0  # seconds between processed scans when still; < 0: never
    resampleThreshold: float = 0.5  # resample when Neff / particles falls below it
    particles: int = 30
    xmin: float = -100.0
    ymin: float = -100.0
    xmax: float = 100.0
    ymax: float = 100.0
    delta: float = 0.05  # metres per cell
    occ_thresh: float = 0.25
    # gmapping's ScanMatcher weighs each candidate's score by exp(-reliability * deviation^2)
    # from the pose it started from; slam_gmapping leaves both at 0 (off). With the linear one
    # off, a narrow laser (the TurtleBot's 57 degrees) looking along a corridor slides down it,
    # so kame keeps the matcher near the odometry's position: a 0.1 m shift costs 10 % of the score.
    linearOdometryReliability: float = 10.0  # per square metre
    angularOdometryReliability: float = 0.0  # per square radian

    def __post_init__(self) -> None:
        if self.particles < 1:
            raise ValueError(f"particles must be at least 1, not {self.particles}")
        if not self.delta > 0:
            raise ValueError(f"delta must be above 0, not {self.delta}")
        if not (self.xmin < self.xmax and self.ymin < self.ymax):
            raise ValueError("the map needs xmin < xmax and ymin < ymax")
        if not self.maxUrange > 0 or self.kernelSize < 0 or self.iterations < 0 or self.lskip < 0:
            raise ValueError("maxUrange must be above 0; kernelSize, iterations and lskip at least 0")
        if not (self.sigma > 0 and self.lsigma > 0 and self.ogain > 0):
            raise ValueError("sigma, lsigma and ogain must be above 0")


@dataclass(frozen=True)
class MapView:
    """A particle's map as nav_msgs/OccupancyGrid wants it: rows from the bottom, -1 unknown."""

    cells: np.ndarray  # int8 (rows, columns)
    origin: tuple[float, float]  # the world position of cell (0, 0)'s corner
    resolution: float


class GridStack:
    """Every particle's hit and visit counts on one shared, growing extent."""

    def __init__(self, particles: int, delta: float) -> None:
        self.delta = delta
        self.origin = (0.0, 0.0)
        self.hits = np.zeros((particles, 0, 0), dtype=np.uint16)
        self.visits = np.zeros((particles, 0, 0), dtype=np.uint16)

    @property
    def shape(self) -> tuple[int, int]:
        return self.hits.shape[1], self.hits.shape[2]

    def cover(self, xmin: float, ymin: float, xmax: float, ymax: float) -> None:
        """Grow (never shrink) so the rectangle lies inside, with room to spare."""
        rows, columns = self.shape
        d = self.delta
        if rows == 0:
            self.origin = (math.floor(xmin / d) * d, math.floor(ymin / d) * d)
        ox, oy = self.origin

        def short(missing: int) -> int:  # cells to add on one side: none, or what lacks and more
            return missing + _GROW if missing > 0 else 0

        left, bottom = short(math.ceil((ox - xmin) / d)), short(math.ceil((oy - ymin) / d))
        right, top = short(math.ceil((xmax - ox) / d) - columns), short(math.ceil((ymax - oy) / d) - rows)
        if left or bottom or right or top:
            padding = ((0, 0), (bottom, top), (left, right))
            self.hits = np.pad(self.hits, padding)
            self.visits = np.pad(self.visits, padding)
            self.origin = (ox - left * d, oy - bottom * d)

    def window(self, xmin: float, ymin: float, xmax: float, ymax: float) -> tuple[slice, slice]:
        """The rows and columns holding the rectangle (clipped to the grid)."""
        rows, columns = self.shape
        c0 = max(0, math.floor((xmin - self.origin[0]) / self.delta))
        r0 = max(0, math.floor((ymin - self.origin[1]) / self.delta))
        c1 = min(columns, math.ceil((xmax - self.origin[0]) / self.delta) + 1)
        r1 = min(rows, math.ceil((ymax - self.origin[1]) / self.delta) + 1)
        return slice(r0, max(r0, r1)), slice(c0, max(c0, c1))


class Gmapping:
    def __init__(self, params: GmappingParams, seed: int = 0) -> None:
        self.params = params
        self.rng = np.random.default_rng(seed)
        n = params.particles
        self.poses = np.zeros((n, 3))
        self.log_weights = np.zeros(n)  # since the last resampling
        self.weight_sums = np.zeros(n)  # over the whole run: gmapping's best particle
        self.grids = GridStack(n, params.delta)
        self.last_odom: Pose | None = None
        self.processed_odom: Pose | None = None
        self.processed_time = -math.inf
        self.linear_distance = self.angular_distance = 0.0
        self.scans_processed = 0
        self.resamples = 0

    # ---------------------------------------------------------------- the filter

    def best(self) -> int:
        return int(np.argmax(self.weight_sums))

    def best_pose(self) -> Pose:
        x, y, theta = self.poses[self.best()]
        return float(x), float(y), float(theta)

    def neff(self) -> float:
        w = self._normalised()
        return float(1.0 / np.sum(w * w))

    def entropy(self) -> float:
        """gmapping's pose entropy: of the particles' normalised weights."""
        w = self._normalised()
        w = w[w > 0]
        return float(-np.sum(w * np.log(w)))

    def _normalised(self) -> np.ndarray:
        gain = 1.0 / (self.params.ogain * len(self.log_weights))
        w = np.exp(gain * (self.log_weights - self.log_weights.max()))
        return np.asarray(w / w.sum())

    def add_scan(self, odom: Pose, ranges: np.ndarray, angles: np.ndarray, range_max: float,
                 stamp: float = 0.0) -> bool:
        """One laser scan (ranges along angles in the robot's frame; inf, nan and <= 0 carry no
        return) taken where the odometry says `odom`. Returns whether it was processed (matched
        and written into the maps), as gmapping's processScan."""
        p = self.params
        ranges = np.nan_to_num(np.asarray(ranges, dtype=float), nan=0.0, posinf=np.inf, neginf=0.0)
        angles = np.asarray(angles, dtype=float)
        if self.last_odom is None:
            self.poses[:] = odom
            self.last_odom = self.processed_odom = odom
            self._register(ranges, angles, range_max)
            self.processed_time = stamp
            self.scans_processed = 1
            return True
        self._move(self.last_odom, odom)
        step = _relative(self.last_odom, odom)
        self.linear_distance += math.hypot(step[0], step[1])
        self.angular_distance += abs(step[2])
        self.last_odom = odom
        due = self.linear_distance >= p.linearUpdate or self.angular_distance >= p.angularUpdate or (
            p.temporalUpdate >= 0 and stamp - self.processed_time > p.temporalUpdate)
        if not due:
            return False
        self.linear_distance = self.angular_distance = 0.0
        self.processed_odom, self.processed_time = odom, stamp
        self._match(ranges, angles, range_max)
        if self.neff() < p.resampleThreshold * p.particles:
            self._resample()
        self._register(ranges, angles, range_max)
        self.scans_processed += 1
        return True

    def _move(self, old: Pose, new: Pose) -> None:
        """gmapping's MotionModel::drawFromMotion for every particle."""
        p = self.params
        dx, dy, dt = _relative(old, new)
        n = len(self.poses)
        sxy = 0.3 * p.srr
        noise = self.rng.standard_normal((n, 3))
        mx = dx + noise[:, 0] * (p.srr * abs(dx) + p.str * abs(dt) + sxy * abs(dy))
        my = dy + noise[:, 1] * (p.srr * abs(dy) + p.str * abs(dt) + sxy * abs(dx))
        mt = dt + noise[:, 2] * (p.stt * abs(dt) + p.srt * math.hypot(dx, dy))
        c, s = np.cos(self.poses[:, 2]), np.sin(self.poses[:, 2])
        self.poses[:, 0] += c * mx - s * my
        self.poses[:, 1] += s * mx + c * my
        self.poses[:, 2] = _wrap(self.poses[:, 2] + mt)

    def _resample(self) -> None:
        """Low-variance (systematic) resampling; every map goes with its particle."""
        w = self._normalised()
        n = len(w)
        positions = (self.rng.random() + np.arange(n)) / n
        chosen = np.minimum(np.searchsorted(np.cumsum(w), positions), n - 1)
        self.poses = self.poses[chosen]
        self.weight_sums = self.weight_sums[chosen]
        self.log_weights = np.zeros(n)
        self.grids.hits = self.grids.hits[chosen]
        self.grids.visits = self.grids.visits[chosen]
        self.resamples += 1

    # ---------------------------------------------------------------- the scan matcher

    def _beams(self, ranges: np.ndarray, range_max: float) -> np.ndarray:
        """Mask of the beams gmapping reads at all (within maxRange, with a return)."""
        limit = self.params.maxRange if self.params.maxRange > 0 else range_max
        return np.asarray(np.isfinite(ranges) & (ranges > 0) & (ranges <= limit))

    def _match(self, ranges: np.ndarray, angles: np.ndarray, range_max: float) -> None:
        p = self.params
        usable = self._beams(ranges, range_max) & (ranges < p.maxUrange)
        index = np.flatnonzero(usable)[:: p.lskip + 1]
        if index.size == 0:
            return
        reach = ranges[index] + _INTO_SURFACE * p.delta
        local = np.column_stack((reach * np.cos(angles[index]), reach * np.sin(angles[index])))
        fields = _Fields(self.grids, self._reach(local), p)
        if fields.empty:
            return
        poses = self.poses.copy()
        particle = np.arange(len(poses))
        # Only beams that pass, from where the particle starts, through space its map has seen
        # just before their end are scored (kame's; gmapping scores all): a beam ending in the
        # unknown scores nothing where the particle is and something once the particle turns or
        # slides to put it on the part of a wall the map holds, which pulls every particle
        # toward what it has seen; a TurtleBot's narrow laser, turning, sees mostly new space.
        counted = fields.seen(self.poses, local, angles[index])
        poses = self._search(fields, poses, local, counted)
        # Only beams that end, from where the particle starts, on a wall its map holds, away from
        # the wall's ends (kame's; gmapping scores all): one ending in the unknown, or beyond the end of what the
        # map has of a wall, scores nothing where the particle is and something once it moves to
        # put the beam on the wall; counting it would pull the particle along a wall toward the
        # part of the wall it has seen
        current = fields.score(particle, poses, local, counted)
        best = np.full(len(poses), -np.inf)
        steps = np.column_stack((np.full(len(poses), p.lstep), np.full(len(poses), p.lstep),
                                 np.full(len(poses), p.astep)))
        refinements = np.zeros(len(poses), dtype=np.int64)
        active = np.ones(len(poses), dtype=bool)
        for _ in range(_MAX_ROUNDS):
            climbing = np.flatnonzero(active)
            if climbing.size == 0:
                break
            refine = best[climbing] >= current[climbing]
            refinements[climbing[refine]] += 1
            steps[climbing[refine]] *= 0.5
            best[climbing] = current[climbing]
            candidates = poses[climbing, None, :] + _MOVES[None, :, :] * steps[climbing, None, :]
            scores = fields.score(np.repeat(climbing, len(_MOVES)), candidates.reshape(-1, 3),
                                  local, counted).reshape(-1, len(_MOVES))
            scores *= self._odometry_gain(candidates, self.poses[climbing, None, :])
            top = np.argmax(scores, axis=1)
            top_score = scores[np.arange(climbing.size), top]
            improved = top_score > current[climbing]
            poses[climbing[improved]] = candidates[np.flatnonzero(improved), top[improved]]
            current[climbing[improved]] = top_score[improved]
            going = (current[climbing] > best[climbing]) | (refinements[climbing] < p.iterations)
            active[climbing[~going]] = False
        accepted = current > p.minimumScore
        self.poses[accepted] = poses[accepted]
        self.poses[:, 2] = _wrap(self.poses[:, 2])
        likelihood = fields.likelihood(particle, self.poses, local)
        self.log_weights += likelihood
        self.weight_sums += likelihood

    def _reach(self, local: np.ndarray) -> tuple[float, float, float, float]:
        """The rectangle where the matcher may look up the beams' ends: around where they end
        from every particle turned to either end of the search, widened by its shifts."""
        p = self.params
        turn = _COARSE_TURNS * p.astep + 2 * p.astep  # the search, then the climb's first steps
        xs, ys = [], []
        for dt in (-turn, 0.0, turn):
            theta = self.poses[:, 2:3] + dt
            xs.append(self.poses[:, 0:1] + np.cos(theta) * local[None, :, 0] - np.sin(theta) * local[None, :, 1])
            ys.append(self.poses[:, 1:2] + np.sin(theta) * local[None, :, 0] + np.cos(theta) * local[None, :, 1])
        sag = float(np.hypot(local[:, 0], local[:, 1]).max()) * (1 - math.cos(turn))
        margin = 4 * p.lstep + (p.kernelSize + 2) * p.delta + sag
        x, y = np.concatenate(xs, axis=1), np.concatenate(ys, axis=1)
        return (float(x.min()) - margin, float(y.min()) - margin, float(x.max()) + margin, float(y.max()) + margin)

    def _search(self, fields: _Fields, poses: np.ndarray, local: np.ndarray, counted: np.ndarray) -> np.ndarray:
        """A correlative search around each particle's pose on the blurred walls (kame's, before
        gmapping's hill climb): the pose in a window of +-2 lstep and +-_COARSE_TURNS astep
        scoring best, the odometry's reliability weighing as in the climb."""
        p = self.params
        pick = np.unique(np.linspace(0, len(local) - 1, min(len(local), _COARSE_BEAMS)).round().astype(np.int64))
        shifts = np.arange(-2, 3) * p.lstep
        turns = np.linspace(-_COARSE_TURNS * p.astep, _COARSE_TURNS * p.astep, 4 * _COARSE_TURNS + 1)
        offsets = np.stack(np.meshgrid(shifts, shifts, turns, indexing="ij"), axis=-1).reshape(-1, 3)
        found = poses.copy()
        for i in range(len(poses)):
            candidates = poses[i] + offsets
            beams = local[pick[counted[i, pick]]]
            scores = fields.coarse_score(np.full(len(candidates), i), candidates, beams)
            scores *= self._odometry_gain(candidates, poses[i][None, :])
            found[i] = candidates[int(np.argmax(scores))]
        return np.asarray(found)

    def _odometry_gain(self, candidates: np.ndarray, start: np.ndarray) -> np.ndarray:
        p = self.params
        shift = np.sum((candidates[..., :2] - start[..., :2]) ** 2, axis=-1)
        turn = _wrap(candidates[..., 2] - start[..., 2]) ** 2
        return np.asarray(np.exp(-p.linearOdometryReliability * shift - p.angularOdometryReliability * turn))

    # ---------------------------------------------------------------- the maps

    def _register(self, ranges: np.ndarray, angles: np.ndarray, range_max: float) -> None:
        """Each particle's map takes the scan from the particle's pose: the cells each beam
        crosses are visited, the one it ends in (within maxUrange) is hit and visited."""
        p = self.params
        readable = self._beams(ranges, range_max)
        if not readable.any():
            return
        reach = np.minimum(ranges[readable], p.maxUrange)
        bearing = angles[readable]
        ends = ranges[readable] < p.maxUrange
        # free space: beams thinned to about half a cell apart at their far end
        spacing = float(np.median(np.abs(np.diff(bearing)))) if bearing.size > 1 else 1.0
        thin = max(1, int(0.5 * p.delta / max(spacing * reach.max(), 1e-9)))
        counts = np.ceil(reach[::thin] / p.delta).astype(np.int64)
        beam = np.repeat(np.arange(counts.size), counts)
        first = np.cumsum(counts) - counts
        along = (np.arange(beam.size) - np.repeat(first, counts)) * p.delta
        free_local = np.column_stack((along * np.cos(bearing[::thin][beam]), along * np.sin(bearing[::thin][beam])))
        into = reach[ends] + _INTO_SURFACE * p.delta
        hit_local = np.column_stack((into * np.cos(bearing[ends]), into * np.sin(bearing[ends])))
        far = float(reach.max()) + p.delta
        xs, ys = self.poses[:, 0], self.poses[:, 1]
        self.grids.cover(float(xs.min()) - far, float(ys.min()) - far, float(xs.max()) + far, float(ys.max()) + far)
        rows, columns = self.grids.window(float(xs.min()) - far, float(ys.min()) - far,
                                          float(xs.max()) + far, float(ys.max()) + far)
        shape = (len(self.poses), rows.stop - rows.start, columns.stop - columns.start)
        free = np.zeros(shape, dtype=bool)
        hit = np.zeros(shape, dtype=bool)
        origin = (self.grids.origin[0] + columns.start * p.delta, self.grids.origin[1] + rows.start * p.delta)
        for mask, points in ((free, free_local), (hit, hit_local)):
            particle, r, c = _cells_of(self.poses, points, origin, p.delta, shape[1:])
            mask[particle, r, c] = True
        free &= ~hit
        hits = self.grids.hits[:, rows, columns]
        visits = self.grids.visits[:, rows, columns]
        if int(visits.max(initial=0)) >= np.iinfo(np.uint16).max - 1:  # keep the ratios, halve the counts
            self.grids.hits //= 2
            self.grids.visits //= 2
        hits += hit
        visits += free | hit

    def occupancy(self, particle: int | None = None) -> MapView:
        """A particle's map (the best's by default) over at least xmin..xmax, ymin..ymax."""
        p = self.params
        index = self.best() if particle is None else particle
        grids = self.grids
        rows, columns = grids.shape
        d = p.delta
        gx0, gy0 = grids.origin
        x0 = min(p.xmin, gx0) if rows else p.xmin
        y0 = min(p.ymin, gy0) if rows else p.ymin
        x0, y0 = (math.floor(x0 / d + 1e-9) * d if rows == 0 else gx0 - math.ceil((gx0 - x0) / d - 1e-9) * d,
                  math.floor(y0 / d + 1e-9) * d if rows == 0 else gy0 - math.ceil((gy0 - y0) / d - 1e-9) * d)
        x1 = max(p.xmax, gx0 + columns * d)
        y1 = max(p.ymax, gy0 + rows * d)
        width, height = round((x1 - x0) / d), round((y1 - y0) / d)
        cells = np.full((height, width), -1, dtype=np.int8)
        if rows:
            hits = grids.hits[index].astype(np.float64)
            visits = grids.visits[index]
            known = np.full(visits.shape, -1, dtype=np.int8)
            seen = visits > 0
            known[seen] = np.where(hits[seen] / visits[seen] > p.occ_thresh, 100, 0)
            r0, c0 = round((gy0 - y0) / d), round((gx0 - x0) / d)
            cells[r0:r0 + rows, c0:c0 + columns] = known
        return MapView(cells, (x0, y0), d)


class _Fields:
    """Every particle's score and likelihood fields over the part of its map a scan can reach:
    from each cell, the distance to the nearest cell at least _FULLNESS occupied within
    kernelSize cells."""

    def __init__(self, grids: GridStack, bounds: tuple[float, float, float, float], p: GmappingParams) -> None:
        self.params = p
        rows, columns = grids.window(*bounds)
        hits = grids.hits[:, rows, columns]
        visits = grids.visits[:, rows, columns]
        self.empty = hits.size == 0
        self.visited = visits > 0
        self.origin = (grids.origin[0] + columns.start * p.delta, grids.origin[1] + rows.start * p.delta)
        occupied = hits.astype(np.float32) > _FULLNESS * visits
        # each cell's class: which distance, among those of the kernel's cells, to the nearest
        # occupied cell of the kernel; the last class is none
        k = p.kernelSize
        offsets = [(dr, dc) for dr in range(-k, k + 1) for dc in range(-k, k + 1)]
        distances = sorted({math.hypot(dr, dc) * p.delta for dr, dc in offsets})
        padded = np.pad(occupied, ((0, 0), (k, k), (k, k)))
        height, width = occupied.shape[1:]
        self.classes: np.ndarray = np.full(occupied.shape, len(distances), dtype=np.uint8)
        for index in range(len(distances) - 1, -1, -1):
            near = np.zeros(occupied.shape, dtype=bool)
            for dr, dc in offsets:
                if abs(math.hypot(dr, dc) * p.delta - distances[index]) < 1e-12:
                    near |= padded[:, k + dr:k + dr + height, k + dc:k + dc + width]
            self.classes[near] = index
        d = np.array(distances)
        self.score_of = np.append(np.exp(-(d ** 2) / (2 * p.sigma ** 2)), 0.0)  # 0 where no wall is near
        self.likelihood_of = np.append(-(d ** 2) / p.lsigma, _NULL_LIKELIHOOD / p.lsigma)
        self.score_grid = self.score_of.astype(np.float32)[self.classes]
        # the correlative search's field: the walls blurred, about 1 on a wall's line
        blur = _COARSE_BLUR * p.sigma / p.delta
        self.coarse_field = np.minimum(1.0, ndimage.gaussian_filter(occupied.astype(np.float32), sigma=(0, blur, blur),
                                                                   mode="constant") * math.sqrt(2 * math.pi) * blur)

    def _points(self, poses: np.ndarray, local: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The beams' ends from each pose, in cells of the window (float32: a cell's 1/1000th)."""
        scale = 1.0 / self.params.delta
        c = (np.cos(poses[:, 2:3]) * scale).astype(np.float32)
        s = (np.sin(poses[:, 2:3]) * scale).astype(np.float32)
        x0 = ((poses[:, 0:1] - self.origin[0]) * scale).astype(np.float32)
        y0 = ((poses[:, 1:2] - self.origin[1]) * scale).astype(np.float32)
        lx, ly = local[None, :, 0].astype(np.float32), local[None, :, 1].astype(np.float32)
        return x0 + c * lx - s * ly, y0 + s * lx + c * ly

    def seen(self, poses: np.ndarray, local: np.ndarray, bearing: np.ndarray) -> np.ndarray:
        """Which beams of each particle, from its pose, pass through space its map has seen
        _SEEN_BEFORE cells before their end."""
        height, width = self.visited.shape[1:]
        before = _SEEN_BEFORE * self.params.delta * np.column_stack((np.cos(bearing), np.sin(bearing)))
        gx, gy = self._points(poses, local - before)
        column, row = np.floor(gx).astype(np.int64), np.floor(gy).astype(np.int64)
        inside = (column >= 0) & (row >= 0) & (column < width) & (row < height)
        particle = np.arange(len(poses))[:, None]
        return np.asarray(inside & self.visited[particle, np.where(inside, row, 0), np.where(inside, column, 0)])

    def coarse_score(self, particle: np.ndarray, poses: np.ndarray, local: np.ndarray) -> np.ndarray:
        field = self.coarse_field
        height, width = field.shape[1:]
        gx, gy = self._points(poses, local)
        column, row = np.floor(gx).astype(np.int64), np.floor(gy).astype(np.int64)
        inside = (column >= 0) & (row >= 0) & (column < width) & (row < height)
        value = field.reshape(-1)[particle[:, None] * (height * width) + np.where(inside, row, 0) * width
                                  + np.where(inside, column, 0)]
        return np.asarray(np.where(inside, value, 0.0).sum(axis=1))

    def score(self, particle: np.ndarray, poses: np.ndarray, local: np.ndarray, counted: np.ndarray) -> np.ndarray:
        """gmapping's match score of each (particle, pose) over the beams counted for the particle:
        bilinear between cell centres."""
        height, width = self.classes.shape[1:]
        gx, gy = self._points(poses, local)
        gx, gy = gx - 0.5, gy - 0.5
        x0, y0 = np.floor(gx), np.floor(gy)
        fx, fy = gx - x0, gy - y0
        x0 = x0.astype(np.int64)
        y0 = y0.astype(np.int64)
        inside = (x0 >= 0) & (y0 >= 0) & (x0 < width - 1) & (y0 < height - 1)
        x0, y0 = np.where(inside, x0, 0), np.where(inside, y0, 0)
        flat = self.score_grid.reshape(-1)
        base = particle[:, None] * (height * width) + y0 * width + x0
        v00, v01 = flat[base], flat[base + 1]
        v10, v11 = flat[base + width], flat[base + width + 1]
        value = (v00 * (1 - fx) + v01 * fx) * (1 - fy) + (v10 * (1 - fx) + v11 * fx) * fy
        return np.asarray(np.where(inside & counted[particle], value, 0.0).sum(axis=1))

    def likelihood(self, particle: np.ndarray, poses: np.ndarray, local: np.ndarray) -> np.ndarray:
        height, width = self.classes.shape[1:]
        gx, gy = self._points(poses, local)
        column, row = np.floor(gx).astype(np.int64), np.floor(gy).astype(np.int64)
        inside = (column >= 0) & (row >= 0) & (column < width) & (row < height)
        classes = self.classes[particle[:, None], np.where(inside, row, 0), np.where(inside, column, 0)]
        value = self.likelihood_of[classes]
        null = _NULL_LIKELIHOOD / self.params.lsigma
        return np.asarray(np.where(inside, value, null).sum(axis=1), dtype=np.float64)


def _cells_of(poses: np.ndarray, local: np.ndarray, origin: tuple[float, float], delta: float,
              shape: tuple[int, int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(particle, row, column) of every local point seen from every pose, inside the window."""
    c, s = np.cos(poses[:, 2:3]), np.sin(poses[:, 2:3])
    x = poses[:, 0:1] + c * local[None, :, 0] - s * local[None, :, 1]
    y = poses[:, 1:2] + s * local[None, :, 0] + c * local[None, :, 1]
    column = np.floor((x - origin[0]) / delta).astype(np.int64)
    row = np.floor((y - origin[1]) / delta).astype(np.int64)
    particle = np.broadcast_to(np.arange(len(poses))[:, None], column.shape)
    inside = (row >= 0) & (row < shape[0]) & (column >= 0) & (column < shape[1])
    return particle[inside], row[inside], column[inside]


def _wrap(angle: np.ndarray) -> np.ndarray:
    return np.asarray(np.remainder(angle + np.pi, 2 * np.pi) - np.pi)


def _relative(a: Pose, b: Pose) -> Pose:
    """b in a's frame."""
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    return c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], 2 * math.pi)
