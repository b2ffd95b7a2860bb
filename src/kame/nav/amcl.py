"""amcl's adaptive Monte Carlo localisation, pure: no ROS, no clock, one seeded generator.

As navigation's amcl 1.17 (pf.c, amcl_odom.cpp, amcl_laser.cpp), on numpy arrays:
- particles are rows (x, y, theta) with weights summing to 1;
- the odometry model is amcl's "diff" (rotate, translate, rotate; noise from odom_alpha1..4),
  with odom_model_type's two readings of the alphas: "diff" (amcl's default, and what the
  TurtleBot's alphas were tuned for) takes alpha * motion^2 as the noise's standard deviation,
  "diff-corrected" as its variance;
- the laser model is the likelihood field: each used beam's end point scores
  z_hit * exp(-d^2 / (2 sigma_hit^2)) + z_rand / range_max, with d the distance to the nearest
  obstacle surface (an occupied cell beside a free or unknown one; capped at
  laser_likelihood_max_dist), and a particle's likelihood is
  1 + sum(score^3); beams at or beyond range_max (and non-finite ones) are skipped;
- resampling draws particles in proportion to weight until the KLD bound for the number of
  histogram bins (0.5 m, 0.5 m, 10 degrees) they fill is met (kld_err, kld_z), between
  min_particles and max_particles; with recovery_alpha_slow/fast set, it injects uniform
  particles as the short-term likelihood falls below the long-term one;
- the estimate is the mean of the heaviest cluster of adjacent histogram bins.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

HISTOGRAM_BIN = (0.5, 0.5, math.radians(10.0))  # pf's kd-tree cell, as amcl sets it


@dataclass(frozen=True)
class FilterParams:
    """The particle filter's and models' parameters, named and defaulted as amcl's."""

    min_particles: int = 100
    max_particles: int = 5000
    kld_err: float = 0.01
    kld_z: float = 0.99
    recovery_alpha_slow: float = 0.0
    recovery_alpha_fast: float = 0.0
    odom_alpha1: float = 0.2  # rotation noise from rotation
    odom_alpha2: float = 0.2  # rotation noise from translation
    odom_alpha3: float = 0.2  # translation noise from translation
    odom_alpha4: float = 0.2  # translation noise from rotation
    odom_model_type: str = "diff"
    laser_z_hit: float = 0.95
    laser_z_rand: float = 0.05
    laser_sigma_hit: float = 0.2
    laser_likelihood_max_dist: float = 2.0
    laser_max_beams: int = 30

    def __post_init__(self) -> None:
        if not (1 <= self.min_particles <= self.max_particles):
            raise ValueError(f"amcl needs 1 <= min_particles <= max_particles "
                             f"(got {self.min_particles}, {self.max_particles})")
        if not (0 < self.kld_err < 1 and 0 < self.kld_z < 1):
            raise ValueError("kld_err and kld_z must lie between 0 and 1")
        if self.odom_model_type not in ("diff", "diff-corrected"):
            raise ValueError(f"odom_model_type must be diff or diff-corrected, not {self.odom_model_type!r}")
        if self.laser_sigma_hit <= 0 or self.laser_max_beams < 2 or self.laser_likelihood_max_dist <= 0:
            raise ValueError("laser_sigma_hit and laser_likelihood_max_dist must be above 0, "
                             "laser_max_beams at least 2")


# amcl's ~initial_pose_* and ~initial_cov_* with their defaults, and the words its warning uses
# for each when the parameter server holds a NaN there (updatePoseFromServer)
INITIAL_POSE_PARAMS = (("initial_pose_x", 0.0, "initial pose X position"),
                       ("initial_pose_y", 0.0, "initial pose Y position"),
                       ("initial_pose_a", 0.0, "initial pose Yaw"),
                       ("initial_cov_xx", 0.5 * 0.5, "initial covariance XX"),
                       ("initial_cov_yy", 0.5 * 0.5, "initial covariance YY"),
                       ("initial_cov_aa", (math.pi / 12.0) ** 2, "initial covariance AA"))


def initial_hypothesis(values: Sequence[float]) -> tuple[tuple[float, float, float], np.ndarray, list[str]]:
    """The filter's starting mean and covariance from the six INITIAL_POSE_PARAMS' values, as
    amcl's updatePoseFromServer: a NaN keeps that parameter's default, with a warning."""
    kept: list[float] = []
    warnings: list[str] = []
    for value, (_, default, words) in zip(values, INITIAL_POSE_PARAMS, strict=True):
        if math.isnan(value):
            warnings.append(f"ignoring NAN in {words}")
            kept.append(default)
        else:
            kept.append(value)
    return (kept[0], kept[1], kept[2]), np.diag(kept[3:]), warnings


def filter_covariance(covariance: Sequence[float]) -> np.ndarray:
    """A PoseWithCovariance's 6x6 covariance (row-major) as the filter's 3x3 (x, y, yaw), as amcl
    reads /initialpose: the x-y block and the yaw variance. amcl leaves the x-yaw and y-yaw terms
    out, so an rviz or user pose carrying them spreads the particles as it would in amcl."""
    full = np.asarray(covariance, dtype=float).reshape(6, 6)
    found = np.zeros((3, 3))
    found[:2, :2] = full[:2, :2]
    found[2, 2] = full[5, 5]
    return found


def message_covariance(covariance: np.ndarray) -> list[float]:
    """The filter's 3x3 covariance as amcl_pose's 6x6 (row-major): the same terms
    filter_covariance reads back, the rest zero."""
    full = np.zeros((6, 6))
    full[:2, :2] = covariance[:2, :2]
    full[5, 5] = covariance[2, 2]
    return [float(v) for v in full.reshape(-1)]


def angle_diff(a: np.ndarray | float, b: np.ndarray | float) -> np.ndarray:
    """a - b, wrapped into [-pi, pi)."""
    return np.asarray((np.asarray(a) - b + math.pi) % (2 * math.pi) - math.pi)


class LikelihoodField:
    """A map's distance field for the laser model, and its free cells for global localisation.
    `cells` is an OccupancyGrid's data (row 0 at the origin's y; -1 unknown, 0..100)."""

    def __init__(self, cells: np.ndarray, resolution: float, origin: tuple[float, float],
                 max_distance: float, occupied_at: int = 65) -> None:
        grid = np.asarray(cells, dtype=np.int16)
        occupied = grid >= occupied_at
        self.occupied = occupied
        self.resolution = float(resolution)
        self.origin = (float(origin[0]), float(origin[1]))
        self.max_distance = float(max_distance)
        # Distances are to the surfaces a laser can hit (occupied cells beside free or unknown
        # ones), as in a map a laser built, whose obstacles have unknown insides. Measured to every
        # occupied cell, a drawn map's solid box would score a beam end deep inside it as a hit,
        # and a particle placed too close to the box (its beams reaching into it) as well as the
        # right one: the filter drifted towards what the robot faced by up to the box's depth.
        surface = occupied & ndimage.binary_dilation(~occupied, structure=np.ones((3, 3), dtype=bool))
        if surface.any():
            distance = ndimage.distance_transform_edt(~surface) * self.resolution
        else:
            distance = np.full(grid.shape, self.max_distance)
        self.distance = np.minimum(distance, self.max_distance)
        self._padded = np.pad(self.distance, 1, constant_values=self.max_distance)
        rows, columns = np.nonzero((grid >= 0) & (grid < 50) & ~occupied)
        self.free = np.column_stack((self.origin[0] + (columns + 0.5) * self.resolution,
                                     self.origin[1] + (rows + 0.5) * self.resolution))

    def distance_at(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Distance to the nearest wall at each point, interpolated between the cells' centres;
        max_distance off the map. Looking up the one cell a point falls in instead would score a
        beam ending on a wall's face 0 from one side and a cell from the other, pulling the
        estimate towards walls met from one side by up to a cell."""
        u = (x - self.origin[0]) / self.resolution - 0.5
        v = (y - self.origin[1]) / self.resolution - 0.5
        rows, columns = self.distance.shape
        inside = (u > -1) & (u < columns) & (v > -1) & (v < rows)
        found = np.full(x.shape, self.max_distance)
        u, v = u[inside], v[inside]
        column, row = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
        fu, fv = u - column, v - row
        padded = self._padded
        c00 = padded[row + 1, column + 1]
        c01 = padded[row + 1, column + 2]
        c10 = padded[row + 2, column + 1]
        c11 = padded[row + 2, column + 2]
        found[inside] = (c00 * (1 - fu) + c01 * fu) * (1 - fv) + (c10 * (1 - fu) + c11 * fu) * fv
        return found

    def is_free(self, x: float, y: float) -> bool:
        column = math.floor((x - self.origin[0]) / self.resolution)
        row = math.floor((y - self.origin[1]) / self.resolution)
        rows, columns = self.distance.shape
        return 0 <= column < columns and 0 <= row < rows and not bool(self.occupied[row, column])


@dataclass(frozen=True)
class Estimate:
    """The heaviest cluster's mean pose and weight, and the whole particle set's 3x3 covariance
    (x, y, theta), as amcl publishes them (pf_cluster_stats' set statistics: the weighted x-y
    block and the headings' circular variance, -2 ln R, with no cross terms to theta)."""

    x: float
    y: float
    theta: float
    covariance: np.ndarray
    weight: float


def kld_limit(bins: int, params: FilterParams) -> int:
    """pf_resample_limit: the sample count that bounds the KLD error for `bins` filled bins."""
    if bins <= 1:
        return params.max_particles
    b = 2.0 / (9.0 * (bins - 1))
    x = 1.0 - b + math.sqrt(b) * params.kld_z
    n = math.ceil((bins - 1) / (2.0 * params.kld_err) * x * x * x)
    return max(params.min_particles, min(params.max_particles, n))


def _bin_keys(particles: np.ndarray) -> np.ndarray:
    return np.column_stack((np.floor(particles[:, 0] / HISTOGRAM_BIN[0]),
                            np.floor(particles[:, 1] / HISTOGRAM_BIN[1]),
                            np.floor(particles[:, 2] / HISTOGRAM_BIN[2]))).astype(np.int64)


class ParticleFilter:
    """The filter's state and the steps amcl takes on it."""

    def __init__(self, params: FilterParams, field: LikelihoodField, seed: int = 0) -> None:
        self.params = params
        self.field = field
        self.rng = np.random.default_rng(seed)
        self.particles = np.zeros((params.max_particles, 3))
        self.weights = np.full(params.max_particles, 1.0 / params.max_particles)
        self._w_slow = 0.0
        self._w_fast = 0.0

    # ---------------------------------------------------------------- initialisation

    def set_gaussian(self, mean: tuple[float, float, float], covariance: np.ndarray) -> None:
        """pf_init: max_particles drawn around `mean` (amcl's /initialpose and initial_pose_*)."""
        drawn = self.rng.multivariate_normal(np.asarray(mean, dtype=float), np.asarray(covariance, dtype=float),
                                             self.params.max_particles)
        drawn[:, 2] = angle_diff(drawn[:, 2], 0.0)
        self._set(drawn)

    def set_uniform(self) -> None:
        """global_localization: max_particles spread over the map's free cells, any heading."""
        self._set(self._uniform(self.params.max_particles))

    def _uniform(self, count: int) -> np.ndarray:
        free = self.field.free
        if len(free) == 0:
            raise ValueError("the map has no free cell to place particles in")
        picked = free[self.rng.integers(0, len(free), count)]
        jitter = self.rng.uniform(-0.5, 0.5, (count, 2)) * self.field.resolution
        headings = self.rng.uniform(-math.pi, math.pi, count)
        return np.column_stack((picked + jitter, headings))

    def _set(self, particles: np.ndarray) -> None:
        self.particles = particles
        self.weights = np.full(len(particles), 1.0 / len(particles))
        self._w_slow = self._w_fast = 0.0

    # ---------------------------------------------------------------- the odometry model

    def predict(self, old: tuple[float, float, float], new: tuple[float, float, float]) -> None:
        """Move every particle by the odometry's motion from `old` to `new` (amcl's diff model)."""
        p = self.params
        dx, dy = new[0] - old[0], new[1] - old[1]
        trans = math.hypot(dx, dy)
        rot1 = 0.0 if trans < 0.01 else float(angle_diff(math.atan2(dy, dx), old[2]))
        rot2 = float(angle_diff(float(angle_diff(new[2], old[2])), rot1))
        rot1_noise = min(abs(float(angle_diff(rot1, 0.0))), abs(float(angle_diff(rot1, math.pi))))
        rot2_noise = min(abs(float(angle_diff(rot2, 0.0))), abs(float(angle_diff(rot2, math.pi))))
        count = len(self.particles)
        normal = self.rng.standard_normal((count, 3))
        # amcl's "diff" hands these sums to pf_ran_gaussian as standard deviations; only
        # "diff-corrected" takes their square roots. Read as variances, the TurtleBot's alphas
        # (0.2) spread the particles some ten times wider than amcl does, 9 cm for each 0.2 rad
        # turned, and the estimate wandered wherever the laser saw a flat wall.
        spread = (lambda v: v) if p.odom_model_type == "diff" else math.sqrt
        rot1_sigma = spread(p.odom_alpha1 * rot1_noise ** 2 + p.odom_alpha2 * trans ** 2)
        trans_sigma = spread(p.odom_alpha3 * trans ** 2 + p.odom_alpha4 * (rot1_noise ** 2 + rot2_noise ** 2))
        rot2_sigma = spread(p.odom_alpha1 * rot2_noise ** 2 + p.odom_alpha2 * trans ** 2)
        rot1_hat = angle_diff(rot1, normal[:, 0] * rot1_sigma)
        trans_hat = trans - normal[:, 1] * trans_sigma
        rot2_hat = angle_diff(rot2, normal[:, 2] * rot2_sigma)
        theta = self.particles[:, 2]
        self.particles = np.column_stack((self.particles[:, 0] + trans_hat * np.cos(theta + rot1_hat),
                                          self.particles[:, 1] + trans_hat * np.sin(theta + rot1_hat),
                                          angle_diff(theta + rot1_hat + rot2_hat, 0.0)))

    # ---------------------------------------------------------------- the laser model

    def weigh(self, ranges: np.ndarray, angles: np.ndarray, range_max: float,
              laser_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> float:
        """Weigh the particles by a scan (angles in the laser's frame, `laser_pose` the laser in
        the base frame); returns the total likelihood before normalising."""
        p = self.params
        ranges = np.asarray(ranges, dtype=float)
        step = max((len(ranges) - 1) / (p.laser_max_beams - 1), 1.0)
        chosen = np.unique(np.round(np.arange(0.0, len(ranges), step)).astype(np.int64).clip(0, len(ranges) - 1))
        r, a = ranges[chosen], np.asarray(angles, dtype=float)[chosen]
        used = np.isfinite(r) & (r < range_max)
        r, a = r[used], a[used]
        if len(r) == 0:
            return 0.0
        xs, ys, ts = self.particles[:, 0], self.particles[:, 1], self.particles[:, 2]
        lx = xs + np.cos(ts) * laser_pose[0] - np.sin(ts) * laser_pose[1]
        ly = ys + np.sin(ts) * laser_pose[0] + np.cos(ts) * laser_pose[1]
        bearing = (ts + laser_pose[2])[:, None] + a[None, :]
        hit_x = lx[:, None] + r[None, :] * np.cos(bearing)
        hit_y = ly[:, None] + r[None, :] * np.sin(bearing)
        z = self.field.distance_at(hit_x, hit_y)
        pz = p.laser_z_hit * np.exp(-z * z / (2 * p.laser_sigma_hit ** 2)) + p.laser_z_rand / range_max
        likelihood = 1.0 + np.sum(pz * pz * pz, axis=1)
        weights = self.weights * likelihood
        total = float(weights.sum())
        if total > 0:
            self.weights = weights / total
            average = float(np.mean(likelihood))  # pf_update_sensor's w_avg
            slow, fast = self._w_slow, self._w_fast
            self._w_slow = average if slow == 0 else slow + p.recovery_alpha_slow * (average - slow)
            self._w_fast = average if fast == 0 else fast + p.recovery_alpha_fast * (average - fast)
        else:
            self.weights = np.full(len(weights), 1.0 / len(weights))
        return total

    # ---------------------------------------------------------------- resampling

    def resample(self) -> None:
        """KLD-sampling: draw by weight until the bound for the bins filled so far is met."""
        p = self.params
        random_share = 0.0
        if self._w_slow > 0 and p.recovery_alpha_slow > 0 and p.recovery_alpha_fast > 0:
            random_share = max(0.0, 1.0 - self._w_fast / self._w_slow)
        drawn = self.particles[self.rng.choice(len(self.particles), p.max_particles, p=self.weights)]
        if random_share > 0:
            injected = self.rng.random(p.max_particles) < random_share
            drawn[injected] = self._uniform(int(injected.sum()))
        keys = _bin_keys(drawn)
        _, first = np.unique(keys, axis=0, return_index=True)
        is_new = np.zeros(len(drawn), dtype=bool)
        is_new[first] = True
        bins_so_far = np.cumsum(is_new)
        limits = np.array([kld_limit(int(k), p) for k in range(bins_so_far[-1] + 1)])
        count = np.arange(1, len(drawn) + 1)
        enough = np.nonzero(count >= limits[bins_so_far])[0]
        keep = int(enough[0]) + 1 if len(enough) else len(drawn)
        keep = max(p.min_particles, min(keep, p.max_particles))
        self.particles = drawn[:keep].copy()
        self.weights = np.full(keep, 1.0 / keep)
        if random_share > 0:
            self._w_slow = self._w_fast = 0.0  # as pf_update_resample resets them after injecting

    # ---------------------------------------------------------------- the estimate

    def estimate(self) -> Estimate:
        """The heaviest cluster of adjacent histogram bins (headings wrap around)."""
        keys = _bin_keys(self.particles)
        low = keys.min(axis=0)
        shape = tuple(int(s) for s in keys.max(axis=0) - low + 1)
        index = keys - low
        occupied = np.zeros(shape, dtype=bool)
        occupied[index[:, 0], index[:, 1], index[:, 2]] = True
        labels, found = ndimage.label(occupied, structure=np.ones((3, 3, 3), dtype=bool))
        labels = _join_wrapped_headings(labels, keys, low)
        of_particle = labels[index[:, 0], index[:, 1], index[:, 2]]
        cluster_weight = np.bincount(of_particle, weights=self.weights, minlength=found + 1)
        best = int(np.argmax(cluster_weight))
        members = of_particle == best
        w = self.weights[members] / cluster_weight[best]
        pts = self.particles[members]
        mean_theta = math.atan2(float(np.sum(w * np.sin(pts[:, 2]))), float(np.sum(w * np.cos(pts[:, 2]))))
        mean = np.array([float(np.sum(w * pts[:, 0])), float(np.sum(w * pts[:, 1])), mean_theta])
        return Estimate(float(mean[0]), float(mean[1]), mean_theta, self._set_covariance(),
                        float(cluster_weight[best]))

    def _set_covariance(self) -> np.ndarray:
        """The covariance amcl publishes: of every particle, not of the heaviest cluster (while
        the belief is split, it stays as wide as the particles are spread)."""
        w = self.weights / self.weights.sum()
        xy = self.particles[:, :2]
        mean = w @ xy
        offsets = xy - mean
        covariance = np.zeros((3, 3))
        covariance[:2, :2] = (offsets * w[:, None]).T @ offsets
        resultant = math.hypot(float(w @ np.cos(self.particles[:, 2])), float(w @ np.sin(self.particles[:, 2])))
        covariance[2, 2] = -2.0 * math.log(max(resultant, 1e-300))
        return covariance


def _join_wrapped_headings(labels: np.ndarray, keys: np.ndarray, low: np.ndarray) -> np.ndarray:
    """Give one label to clusters that meet across theta = +-pi (the first and last heading bins)."""
    bins_around = round(2 * math.pi / HISTOGRAM_BIN[2])
    first, last = -bins_around // 2, math.ceil(math.pi / HISTOGRAM_BIN[2]) - 1
    if not (keys[:, 2].min() <= first and keys[:, 2].max() >= last):
        return labels
    low_slice, high_slice = labels[:, :, first - low[2]], labels[:, :, last - low[2]]
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            shifted = np.roll(np.roll(high_slice, dx, axis=0), dy, axis=1)
            for a, b in set(zip(low_slice[(low_slice > 0) & (shifted > 0)].tolist(),
                                shifted[(low_slice > 0) & (shifted > 0)].tolist(), strict=True)):
                if a != b:
                    labels[labels == b] = a
                    low_slice, high_slice = labels[:, :, first - low[2]], labels[:, :, last - low[2]]
    return labels
