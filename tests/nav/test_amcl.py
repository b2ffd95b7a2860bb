"""amcl's particle filter on the 2-D world, without ROS: the models, KLD sampling, the estimate,
and global localisation in the office world converging after a scripted drive."""

from __future__ import annotations

import math

import numpy as np
import pytest

from kame.nav.amcl import (
    FilterParams,
    LikelihoodField,
    ParticleFilter,
    angle_diff,
    filter_covariance,
    initial_hypothesis,
    kld_limit,
    message_covariance,
)
from kame.stage.world import LaserModel, OdometryModel, Walls, World
from tests.nav.worlds import load_world_map

# Through the office: a turn on the spot in the corridor (which alone is symmetric under a half
# turn), into the south room with the box, a turn there, and back out east along the corridor.
OFFICE_DRIVE = [(0.0, 1.0, 6.3), (0.5, 0.0, 4.0), (0.0, -1.0, 1.62), (0.5, 0.0, 5.0), (0.0, 1.0, 6.3),
                (0.0, 1.0, 3.18), (0.5, 0.0, 5.0), (0.0, -1.0, 1.62), (0.4, 0.0, 4.0)]


def office_filter(params: FilterParams, seed: int) -> ParticleFilter:
    grid = load_world_map("office")
    field = LikelihoodField(grid.cells, grid.resolution, grid.origin[:2], params.laser_likelihood_max_dist)
    return ParticleFilter(params, field, seed=seed)


def drive(world: World, pf: ParticleFilter, plan: list[tuple[float, float, float]], resample_interval: int = 2,
          update_min_d: float = 0.2, update_min_a: float = math.pi / 6) -> None:
    """amcl's loop: a filter update whenever odometry moved update_min_d or turned update_min_a."""
    laser = world.laser
    last: tuple[float, float, float] | None = None
    updates = 0
    for linear, angular, seconds in plan:
        for _ in range(round(seconds / 0.05)):
            world.command("bot", linear, angular)
            world.step(0.05)
            odom = world.robot("bot").odom
            now = (odom.x, odom.y, odom.theta)
            if last is not None and math.hypot(now[0] - last[0], now[1] - last[1]) < update_min_d \
                    and abs(float(angle_diff(now[2], last[2]))) < update_min_a:
                continue
            if last is not None:
                pf.predict(last, now)
            last = now
            pf.weigh(world.scans(["bot"])["bot"], laser.angles(), laser.range_max)
            updates += 1
            if updates % resample_interval == 0:
                pf.resample()


@pytest.mark.parametrize("seed", [1, 2])
def test_global_localisation_converges_in_the_office(seed: int) -> None:
    world = World(Walls(load_world_map("office")), laser=LaserModel(noise=0.01), seed=seed)
    world.spawn("bot", 0.0, 0.0, 0.0)
    # amcl's "diff" model reads the default alphas as standard deviations: too little spread for
    # the belief to keep the corridor's mirror image alive until the box room tells them apart
    # (3 seeds in 6 settle on the mirror); its "diff-corrected" reading spreads them enough
    pf = office_filter(FilterParams(odom_model_type="diff-corrected"), seed=seed)
    pf.set_uniform()
    before = pf.estimate()
    drive(world, pf, OFFICE_DRIVE)
    truth = world.robot("bot").pose
    found = pf.estimate()
    assert math.hypot(found.x - truth.x, found.y - truth.y) < 0.2
    assert abs(math.degrees(float(angle_diff(found.theta, truth.theta)))) < 10
    assert found.weight > 0.9  # one cluster holds the belief, a tight one; at the start it spread over the map
    # the covariance is the whole set's, as amcl publishes it: the few particles outside the cluster widen it
    assert np.sqrt(np.diag(found.covariance)[:2]).max() < 0.25
    assert np.sqrt(np.diag(before.covariance)[:2]).min() > 2.0


def test_the_estimate_is_the_heaviest_clusters_pose_with_the_whole_sets_covariance() -> None:
    """amcl publishes the heaviest cluster's mean with pf_cluster_stats' set covariance: a belief
    split 60/40 between two places 4 m apart is at the heavier one, with a spread that spans both."""
    pf = office_filter(FilterParams(), seed=1)
    count = len(pf.particles)
    heavier = np.arange(count) < 0.6 * count
    pf.particles = np.zeros((count, 3))
    pf.particles[~heavier, 0] = 4.0
    pf.particles[:, 2] = np.where(heavier, 0.1, -0.1)
    pf.weights = np.full(count, 1.0 / count)
    estimate = pf.estimate()
    assert (estimate.x, estimate.y, estimate.theta) == pytest.approx((0.0, 0.0, 0.1))
    share = heavier.mean()
    assert estimate.covariance[0, 0] == pytest.approx(16 * share * (1 - share))  # both places' spread
    assert estimate.covariance[1, 1] == pytest.approx(0.0, abs=1e-12)
    # the headings' circular variance, -2 ln R, and no cross terms to theta (amcl has none)
    resultant = math.hypot(math.cos(0.1), share * math.sin(0.1) - (1 - share) * math.sin(0.1))
    assert estimate.covariance[2, 2] == pytest.approx(-2 * math.log(resultant))
    assert estimate.covariance[0, 2] == estimate.covariance[2, 0] == 0.0


def test_tracking_from_a_wrong_initial_pose() -> None:
    world = World(Walls(load_world_map("office")), laser=LaserModel(noise=0.01), seed=5)
    world.spawn("bot", 0.0, 0.0, 0.0)
    pf = office_filter(FilterParams(min_particles=500, max_particles=2000), seed=5)
    pf.set_gaussian((0.4, -0.3, 0.3), np.diag([0.25, 0.25, (math.pi / 12) ** 2]))
    drive(world, pf, [(0.4, 0.0, 5.0), (0.0, 1.0, 3.2), (0.4, 0.0, 4.0)])
    truth, found = world.robot("bot").pose, pf.estimate()
    assert math.hypot(found.x - truth.x, found.y - truth.y) < 0.2
    assert abs(math.degrees(float(angle_diff(found.theta, truth.theta)))) < 10


def test_the_odometry_model_without_noise_follows_the_odometry() -> None:
    quiet = FilterParams(odom_alpha1=0.0, odom_alpha2=0.0, odom_alpha3=0.0, odom_alpha4=0.0, min_particles=3,
                         max_particles=3)
    pf = office_filter(quiet, seed=0)
    pf._set(np.array([[0.0, 0.0, 0.0], [1.0, 1.0, math.pi / 2], [2.0, 0.0, math.pi]]))
    pf.predict((5.0, 5.0, math.pi / 2), (5.0, 6.0, math.pi))  # one metre ahead, then a quarter turn left
    np.testing.assert_allclose(pf.particles, [[1.0, 0.0, math.pi / 2], [1.0, 2.0, -math.pi], [1.0, 0.0, -math.pi / 2]],
                               atol=1e-9)


def test_diff_reads_the_alphas_as_deviations_and_diff_corrected_as_variances() -> None:
    spreads = {}
    for model in ("diff", "diff-corrected"):
        pf = office_filter(FilterParams(odom_model_type=model, min_particles=2000, max_particles=2000), seed=0)
        pf._set(np.zeros((2000, 3)))
        pf.predict((0.0, 0.0, 0.0), (0.0, 0.0, 0.2))  # a 0.2 rad turn on the spot
        spreads[model] = float(np.std(np.hypot(pf.particles[:, 0], pf.particles[:, 1]) * np.sign(pf.particles[:, 0])))
    assert spreads["diff"] == pytest.approx(0.2 * 0.2 ** 2, rel=0.1)  # alpha4 * rot^2 metres
    assert spreads["diff-corrected"] == pytest.approx(math.sqrt(0.2 * 0.2 ** 2), rel=0.1)
    with pytest.raises(ValueError, match="odom_model_type"):
        FilterParams(odom_model_type="omni")


def test_odometry_noise_grows_with_the_motion() -> None:
    pf = office_filter(FilterParams(min_particles=2000, max_particles=2000), seed=0)
    pf._set(np.zeros((2000, 3)))
    pf.predict((0.0, 0.0, 0.0), (0.5, 0.0, 0.0))
    short = np.hypot(pf.particles[:, 0], pf.particles[:, 1])
    pf._set(np.zeros((2000, 3)))
    pf.predict((0.0, 0.0, 0.0), (2.0, 0.0, 0.0))
    long = np.hypot(pf.particles[:, 0], pf.particles[:, 1])
    assert long.std() > 3 * short.std()
    assert abs(np.median(long) - 2.0) < 0.05 and abs(np.median(short) - 0.5) < 0.02


def test_the_laser_model_prefers_the_true_pose() -> None:
    world = World(Walls(load_world_map("office")), odometry=OdometryModel(0.0, 0.0))
    world.spawn("bot", 2.0, -2.5, -2.2)
    pf = office_filter(FilterParams(min_particles=4, max_particles=4), seed=0)
    pf._set(np.array([[2.0, -2.5, -2.2], [2.2, -2.5, -2.2], [2.0, -2.5, -2.0], [-2.0, 2.5, 0.94]]))
    pf.weigh(world.scans(["bot"])["bot"], world.laser.angles(), world.laser.range_max)
    assert int(np.argmax(pf.weights)) == 0
    assert pf.weights[0] > 1.5 * pf.weights[1:].max()


def test_a_pose_too_close_to_a_solid_box_scores_worse_than_the_true_one() -> None:
    """Facing the south room's box (drawn solid on the map) with the TurtleBot's amcl parameters:
    a particle 0.3 m closer puts its beam ends inside the box, which must not count as hits."""
    world = World(Walls(load_world_map("office")), odometry=OdometryModel(0.0, 0.0))
    world.spawn("bot", 2.0, -3.0, -math.pi / 2)
    turtlebot = FilterParams(min_particles=2, max_particles=2, laser_z_hit=0.5, laser_z_rand=0.5, laser_max_beams=60)
    pf = office_filter(turtlebot, seed=0)
    pf._set(np.array([[2.0, -3.0, -math.pi / 2], [2.0, -3.3, -math.pi / 2]]))
    pf.weigh(world.scans(["bot"])["bot"], world.laser.angles(), world.laser.range_max)
    assert pf.weights[0] > 2 * pf.weights[1]
    assert pf.field.is_free(2.0, -3.0) and not pf.field.is_free(2.0, -4.3)  # the box's inside is no free space


def test_kld_bound() -> None:
    params = FilterParams()
    assert kld_limit(1, params) == params.max_particles  # one bin says nothing: keep them all
    assert kld_limit(2, params) == params.min_particles
    assert kld_limit(10, params) < kld_limit(50, params) <= params.max_particles
    # pf_resample_limit's formula for 50 bins: 49 / 0.02 * (1 - b + sqrt(b) * 0.99)^3, b = 2 / 441
    b = 2 / (9 * 49)
    assert kld_limit(50, params) == math.ceil(49 / 0.02 * (1 - b + math.sqrt(b) * 0.99) ** 3)


def test_resampling_shrinks_a_concentrated_belief() -> None:
    pf = office_filter(FilterParams(), seed=0)
    pf.set_gaussian((0.0, 0.0, 0.0), np.diag([0.01, 0.01, 0.001]))
    pf.resample()
    assert pf.params.min_particles <= len(pf.particles) < 1000
    pf.set_uniform()
    pf.resample()
    assert len(pf.particles) == pf.params.max_particles


def test_the_estimate_joins_a_cluster_across_the_half_turn() -> None:
    pf = office_filter(FilterParams(min_particles=100, max_particles=400), seed=0)
    rng = np.random.default_rng(0)
    near_pi = np.column_stack((rng.normal(1.0, 0.05, 300), rng.normal(0.0, 0.05, 300),
                               angle_diff(rng.normal(math.pi, 0.05, 300), 0.0)))
    elsewhere = np.column_stack((rng.normal(-3.0, 0.05, 100), rng.normal(0.0, 0.05, 100), np.zeros(100)))
    pf._set(np.vstack((near_pi, elsewhere)))
    found = pf.estimate()
    assert found.weight == pytest.approx(0.75)
    assert abs(found.x - 1.0) < 0.02 and abs(float(angle_diff(found.theta, math.pi))) < 0.02


def test_bad_parameters_are_refused() -> None:
    with pytest.raises(ValueError, match="min_particles"):
        FilterParams(min_particles=10, max_particles=5)


def test_an_initial_pose_covariance_keeps_the_xy_block_and_the_yaw_variance_only() -> None:
    """amcl's handleInitialPoseMessage reads covariance[6i+j] for i, j in {x, y} and [35]: the
    x-yaw and y-yaw terms a 6x6 covariance carries (and z, roll, pitch) do not shape the particles."""
    full = np.arange(36, dtype=float).reshape(6, 6) + 100.0
    assert filter_covariance(list(full.reshape(-1))).tolist() == [[100.0, 101.0, 0.0], [106.0, 107.0, 0.0],
                                                                  [0.0, 0.0, 135.0]]
    params = FilterParams(min_particles=100, max_particles=4000)
    pf = office_filter(params, seed=3)
    correlated = np.zeros((6, 6))
    correlated[0, 0] = correlated[5, 5] = 0.04
    correlated[0, 5] = correlated[5, 0] = 0.039  # x and yaw almost one variable
    pf.set_gaussian((0.0, 0.0, 0.0), filter_covariance(list(correlated.reshape(-1))))
    assert abs(np.corrcoef(pf.particles[:, 0], pf.particles[:, 2])[0, 1]) < 0.1


def test_amcl_pose_carries_the_terms_an_initial_pose_is_read_from() -> None:
    """amcl_pose's 6x6 covariance, as amcl fills it: the x-y block and the yaw variance, the rest
    zero; read back as an initial pose it is the same 3x3 without the yaw cross terms."""
    estimate = np.array([[0.04, 0.01, 0.02], [0.01, 0.09, 0.03], [0.02, 0.03, 0.05]])
    full = np.asarray(message_covariance(estimate)).reshape(6, 6)
    assert np.count_nonzero(full) == 5 and full[5, 5] == 0.05 and full[0, 1] == full[1, 0] == 0.01
    assert filter_covariance(list(full.reshape(-1))).tolist() == [[0.04, 0.01, 0.0], [0.01, 0.09, 0.0],
                                                                  [0.0, 0.0, 0.05]]


def test_initial_pose_parameters_ignore_a_nan_as_amcl_does() -> None:
    mean, covariance, warnings = initial_hypothesis([1.0, math.nan, 0.5, 0.1, 0.2, math.nan])
    assert mean == (1.0, 0.0, 0.5)
    assert np.diag(covariance).tolist() == [0.1, 0.2, (math.pi / 12) ** 2]
    assert np.count_nonzero(covariance - np.diag(np.diag(covariance))) == 0
    assert warnings == ["ignoring NAN in initial pose Y position", "ignoring NAN in initial covariance AA"]
    assert initial_hypothesis([0.0] * 6)[2] == []
