"""View gains through the bindings, against counts numpy makes from the frustum's definition."""

import numpy as np
import pytest

import vantage as vt

FOV = vt.SensorFov.from_degrees(57, 43, 0.3, 2.5)


def cells_in_view(spec, pose, fov):
    """Cells whose centre lies inside the frustum (docs/model.md, 'One view'), by brute force."""
    i, j, k = np.meshgrid(*(np.arange(n) for n in spec.shape), indexing="ij")
    centres = spec.origin + (np.stack([i, j, k], axis=-1) + 0.5) * spec.resolution
    local = (centres - pose[:3, 3]) @ pose[:3, :3]  # into the sensor frame
    x, y, z = local[..., 0], local[..., 1], local[..., 2]
    r = np.linalg.norm(local, axis=-1)
    return ((x > 0) & (r >= fov.min_range) & (r <= fov.max_range)
            & (np.abs(y) <= x * np.tan(fov.h_fov / 2)) & (np.abs(z) <= x * np.tan(fov.v_fov / 2)))


@pytest.fixture
def setup():
    spec = vt.GridSpec.centered((0, 0, 0.2), 0.04, (20, 20, 10))
    rng = np.random.default_rng(11)
    p = rng.choice([0.12, 0.5, 0.97], size=spec.shape, p=[0.3, 0.6, 0.1])
    grid = vt.OccupancyGrid(spec)
    grid.set_probabilities(p)
    poses = vt.ring_poses((0, 0, 0.2), radius=1.2, height=0.8, positions=4)
    return spec, grid, poses


def test_exact_targets_are_the_unobserved_cells_in_view(setup):
    spec, grid, poses = setup
    gains = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(evaluation="exact"))
    assert len(gains) == len(poses) == 12
    unobserved = grid.states() == vt.UNOBSERVED
    for pose, g in zip(poses, gains):
        assert g.targets == np.count_nonzero(unobserved & cells_in_view(spec, pose, FOV))
        assert 0.0 < g.gain < g.targets  # a cell holds at most one bit


def test_greedy_gain_counts_every_target_of_an_unknown_grid():
    spec = vt.GridSpec.centered((0, 0, 0), 0.05, (16, 16, 16))
    grid = vt.OccupancyGrid(spec)  # all unobserved: nothing occupied blocks any ray
    poses = np.stack([vt.look_at((1.5, 0.2, 0.3), (0, 0, 0)), vt.look_at((0, -1.4, 0.5), (0, 0, 0))])
    gains = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(method="greedy", evaluation="exact"))
    for pose, g in zip(poses, gains):
        assert g.targets == np.count_nonzero(cells_in_view(spec, pose, FOV)) > 0
        assert g.gain == g.targets


def test_known_grid_has_no_gain(setup):
    spec, grid, poses = setup
    grid.set_probabilities(np.full(spec.shape, 0.12))
    for g in vt.evaluate_views(grid, poses, FOV):
        assert g.gain == 0.0 and g.targets == 0


def test_auto_is_exact_and_threads_do_not_matter(setup):
    _, grid, poses = setup
    exact = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(evaluation="exact"))
    auto = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(evaluation="auto"))
    assert [g.gain for g in auto] == [g.gain for g in exact]
    one = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(num_threads=1))
    two = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(num_threads=2))
    assert [g.gain for g in one] == [g.gain for g in two]
    with pytest.raises(ValueError, match="fast"):  # removed: the exact one costs as little
        vt.GainConfig(evaluation="fast")


def test_plan_chooses_the_highest_gain(setup):
    _, grid, poses = setup
    plan = vt.plan_next_view(grid, poses, FOV)  # `vantage plan`'s: survival, the swept search
    assert plan.search == "swept"
    every = vt.plan_next_view(grid, poses, FOV, vt.PlannerConfig(search="exhaustive"))
    assert every.best == int(np.argmax([g.cells for g in every.gains]))  # it ranks by cells
    assert plan.best == every.best
    paper = vt.PlannerConfig(method="probabilistic", search="exhaustive")
    bits = vt.plan_next_view(grid, poses, FOV, paper)
    assert bits.best == int(np.argmax([g.gain for g in bits.gains]))
    assert plan.ranking[0] == plan.best and sorted(plan.ranking) == list(range(len(poses)))
    assert plan.greedy_gains == []  # not asked for
    greedy = vt.plan_next_view(grid, poses, FOV, vt.PlannerConfig(method="greedy"))
    counted = vt.plan_next_view(
        grid, poses, FOV, vt.PlannerConfig(method="greedy", search="exhaustive"))
    assert greedy.best == int(np.argmax(counted.scores))


def test_expected_cells_seen_lie_between_nothing_and_every_target(setup):
    _, grid, poses = setup
    prob = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(evaluation="exact"))
    greedy = vt.evaluate_views(grid, poses, FOV, vt.GainConfig(method="greedy", evaluation="exact"))
    for p, g in zip(prob, greedy):
        assert 0.0 < p.cells <= p.targets  # each target is seen with a probability
        assert g.cells == g.gain  # greedy's prediction in cells is its count
