"""The grid through the bindings: shapes and indexing of its arrays, integration against what a
ray must do, and OctoMap files."""

import numpy as np
import pytest

import vantage as vt

FOV = vt.SensorFov.from_degrees(57, 43, 0.1, 3.0)


@pytest.fixture
def spec():
    return vt.GridSpec(origin=(0.0, -0.5, -0.5), resolution=0.05, dims=(40, 20, 20))


def test_arrays_have_the_grid_shape_and_index_order(spec):
    grid = vt.OccupancyGrid(spec)
    assert grid.shape == spec.shape == (40, 20, 20)
    p = np.full(spec.shape, 0.5)
    p[3, 7, 11] = 0.9
    p[39, 0, 19] = 0.2  # inside the clamp [0.12, 0.97]
    grid.set_probabilities(p)
    np.testing.assert_allclose(grid.probabilities(), p, atol=1e-6)
    states = grid.states()
    assert states.dtype == np.uint8 and states.shape == spec.shape
    assert states[3, 7, 11] == vt.OCCUPIED and states[39, 0, 19] == vt.FREE
    assert grid.counts() == {"unobserved": spec.num_cells - 2, "free": 1, "occupied": 1}
    assert spec.index_of(spec.center(3, 7, 11)) == (3, 7, 11)


def test_set_probabilities_checks_every_value_first(spec):
    grid = vt.OccupancyGrid(spec)
    p = np.full(spec.shape, 0.9)
    p[5, 6, 7] = 1.5
    with pytest.raises(ValueError, match=r"probabilities\[5, 6, 7\] = 1.5 lies outside"):
        grid.set_probabilities(p)
    assert grid.counts()["unobserved"] == spec.num_cells  # unchanged
    with pytest.raises(ValueError, match="grid's shape"):
        grid.set_probabilities(np.full((2, 2, 2), 0.5))


def test_endpoint_integration_hits_the_end_and_misses_the_way(spec):
    # A sensor at x = 0 looking along +x; one point 1.5 m ahead on the axis.
    grid = vt.OccupancyGrid(spec)
    pose = np.eye(4)
    pose[:3, 3] = [0.01, 0.01, 0.01]
    point = np.array([[1.51, 0.01, 0.01]])
    result = grid.integrate(point, pose, FOV, mode="endpoint")
    assert result.points_inside == 1 and result.hit_cells == 1
    states = grid.states()
    hit = spec.index_of(point[0])
    assert states[hit] == vt.OCCUPIED
    _, j, k = hit
    assert np.all(states[: hit[0], j, k] == vt.FREE)  # every cell the ray crossed
    assert np.all(states[hit[0] + 1:, j, k] == vt.UNOBSERVED)  # nothing behind it
    assert result.missed_cells == hit[0]
    assert result.left_unobserved == hit[0] + 1
    assert grid.counts()["free"] + grid.counts()["occupied"] == hit[0] + 1


def test_paper_integration_is_the_same_for_any_thread_count(spec):
    rng = np.random.default_rng(7)
    points = np.column_stack([np.full(500, 1.5), rng.uniform(-0.3, 0.3, (500, 2))])
    grids = []
    for threads in (1, 2):
        grid = vt.OccupancyGrid(spec)
        grid.integrate(points, np.eye(4), FOV, mode="paper", num_threads=threads)
        grids.append(grid.log_odds())
    np.testing.assert_array_equal(grids[0], grids[1])
    assert np.count_nonzero(grids[0] > 0) > 0


def test_octomap_round_trips(spec, tmp_path):
    grid = vt.OccupancyGrid(spec)
    rng = np.random.default_rng(3)
    grid.set_probabilities(rng.choice([0.2, 0.45, 0.5, 0.55, 0.8], size=spec.shape))
    wrote = grid.save(tmp_path / "map.ot")
    assert wrote["format"] == "ot"
    assert wrote["occupied_cells"] == grid.counts()["occupied"]
    full = vt.OccupancyGrid.load(tmp_path / "map.ot", spec=spec)
    np.testing.assert_array_equal(full.log_odds(), grid.log_odds())  # .ot keeps every value
    grid.save(str(tmp_path / "map.bt"))
    binary = vt.OccupancyGrid.load(tmp_path / "map.bt", spec=spec)
    np.testing.assert_array_equal(binary.states(), grid.states())  # .bt keeps the classes
    derived = vt.OccupancyGrid.load(tmp_path / "map.bt")  # the box of the known voxels
    assert derived.counts()["occupied"] == grid.counts()["occupied"]


def test_a_saved_bt_loads_back_as_the_same_grid(tmp_path):
    """save() says which grid it wrote; load(spec=) of that gives it back. Without spec a grid
    whose every cell is known, on OctoMap's lattice, comes back the same too."""
    spec = vt.GridSpec((-0.5, 0.25, 0.0), 0.05, (12, 8, 6))  # on the lattice: 0.05 divides it
    grid = vt.OccupancyGrid(spec)
    rng = np.random.default_rng(5)
    grid.set_probabilities(rng.choice([0.2, 0.8], size=spec.shape))
    wrote = grid.save(tmp_path / "map.bt")
    assert wrote["spec"] == spec
    same = vt.OccupancyGrid.load(tmp_path / "map.bt", spec=wrote["spec"])
    np.testing.assert_array_equal(same.states(), grid.states())
    derived = vt.OccupancyGrid.load(tmp_path / "map.bt")
    assert derived.spec == spec
    np.testing.assert_array_equal(derived.states(), grid.states())
    assert "spec=" in vt.OccupancyGrid.load.__doc__


def test_a_plan_says_what_it_chose(spec):
    grid = vt.OccupancyGrid(spec)
    candidates = vt.ring_candidates(spec)
    plan = vt.plan_next_view(grid, candidates, FOV, vt.PlannerConfig(method="greedy"))
    text = repr(plan)
    assert text.startswith(f"Plan(best={plan.best}, candidates={len(candidates)}, ")
    assert f"score={plan.scores[plan.best]:g}" in text, text


def test_the_planner_takes_the_clis_settings(spec):
    """PlannerConfig names what `vantage explore` names: the method's own objective, the search
    (by default the fastest that serves the method), the swept search's rays, the sequence; bad
    values, and a search that does not serve the method, raise ValueError."""
    sequence = vt.PlannerConfig(method="sequence")
    assert (sequence.objective, sequence.horizon, sequence.search) == ("cells", 3, "sequence")
    assert vt.PlannerConfig(method="probabilistic").objective == "bits"
    assert vt.PlannerConfig(method="probabilistic").search == "pruned"
    assert vt.PlannerConfig(method="survival").search == "swept"
    assert vt.PlannerConfig(method="unobserved-voxel").search == "swept"
    grid = vt.OccupancyGrid(spec)
    candidates = vt.ring_candidates(spec)
    exact = vt.plan_next_view(
        grid, candidates, FOV, vt.PlannerConfig(method="survival", search="exhaustive"))
    assert exact.search == "exhaustive" and not any(exact.estimated)
    proven = vt.plan_next_view(
        grid, candidates, FOV, vt.PlannerConfig(method="survival", search="pruned"))
    assert proven.search == "pruned" and proven.best == exact.best
    planned = vt.plan_next_view(grid, candidates, FOV, sequence)
    assert 0 <= planned.best < len(candidates)
    swept = vt.PlannerConfig(method="survival", search="swept", swept_rays=48)
    assert (swept.search, swept.swept_rays) == ("swept", 48)
    # An empty grid's ring ties many views exactly: the swept search's choice scores the best.
    chosen = vt.plan_next_view(grid, candidates, FOV, swept)
    assert chosen.search == "swept" and not chosen.estimated[chosen.best]
    assert chosen.scores[chosen.best] == pytest.approx(exact.scores[exact.best], rel=1e-9)
    assert chosen.ranking[0] == chosen.best
    with pytest.raises(ValueError, match="swept_rays"):
        vt.PlannerConfig(method="survival", search="swept", swept_rays=0)
    with pytest.raises(ValueError, match="power of two"):
        vt.PlannerConfig(method="greedy", sample=3)
    with pytest.raises(ValueError, match="by cells"):
        vt.PlannerConfig(method="sequence", objective="bits")
    with pytest.raises(ValueError, match="decision search"):
        vt.PlannerConfig(search="best")
    with pytest.raises(ValueError, match="does not serve random"):
        vt.PlannerConfig(method="random", search="swept")


def test_a_copy_is_independent(spec):
    grid = vt.OccupancyGrid(spec)
    copy = grid.copy()
    copy.set_probabilities(np.full(spec.shape, 0.9))
    assert grid.counts()["occupied"] == 0 and copy.counts()["occupied"] == spec.num_cells
