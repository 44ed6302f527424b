"""The bindings plan as `vantage plan` does: on the own-scans example (examples/own-scans), the
same map, the same gains bit for bit and the same ranking as the CLI's plan.json."""

import numpy as np
import pytest

import vantage as vt


@pytest.fixture(scope="module")
def planned(own_scans):
    folder, cli, _ = own_scans
    manifest = vt.read_manifest(folder)
    clouds = [vt.read_point_cloud(c["file"]) for c in manifest["clouds"]]
    poses = np.stack([c["T_world_cloud"] for c in manifest["clouds"]])
    candidates = vt.ring_candidates(manifest["roi"])  # what `vantage plan` uses by default
    grid, plan = vt.plan(clouds, poses, manifest["fov"], manifest["grid"], candidates,
                         frame=manifest["frame"],
                         table_segmentation=manifest["table_segmentation"],
                         icp=manifest["icp"], integration=manifest["integration"])
    return manifest, candidates, grid, plan, cli


def test_the_manifest_reads_as_written(own_scans):
    folder, _, _ = own_scans
    manifest = vt.read_manifest(folder / "manifest.yaml")
    assert [c["file"].name for c in manifest["clouds"]] == ["west.pcd", "south.pcd"]
    np.testing.assert_array_equal(manifest["clouds"][0]["T_world_cloud"][:3, 3], [-1.0, 0, 1.1])
    assert manifest["frame"] == "x_forward"
    assert manifest["table_segmentation"] and not manifest["icp"]
    assert manifest["grid"].resolution == 0.0078125
    assert manifest["fov"] == vt.SensorFov.from_degrees(90, 45, 0.1, 3.0)


def test_same_map_as_the_cli(planned, own_scans):
    _, _, grid, _, cli = planned
    counts = grid.counts()
    for key in ("unobserved", "free", "occupied"):
        assert counts[key] == cli["map"][key], key
    assert counts["occupied"] > 0 and counts["free"] > 0
    spec = grid.spec
    assert list(spec.dims) == cli["map"]["grid"]["dims"]
    assert spec.resolution == cli["map"]["grid"]["resolution"]
    np.testing.assert_array_equal(spec.origin, cli["map"]["grid"]["origin"])
    # The CLI's map.bt holds the same classes, cell by cell.
    _, _, out = own_scans
    written = vt.OccupancyGrid.load(out / "map.bt", spec=spec)
    np.testing.assert_array_equal(written.states(), grid.states())


def test_map_recorded_reads_the_files_to_the_same_grid(planned, own_scans):
    folder, _, _ = own_scans
    _, _, grid, _, _ = planned
    from_files = vt.map_recorded(folder)
    np.testing.assert_array_equal(from_files.log_odds(), grid.log_odds())


def test_same_candidates_gains_and_ranking_as_the_cli(planned):
    _, candidates, _, plan, cli = planned
    assert len(cli["candidates"]) == len(candidates) == 30
    assert plan.best == cli["next_best_view"]["index"]
    assert plan.ranking == [c["index"] for c in cli["candidates"]]
    for c in cli["candidates"]:
        i = c["index"]
        np.testing.assert_array_equal(candidates[i][:3, 3], c["sensor"]["position"])
        # The same orientation: quaternion x, y, z, w of the CLI's (up to sign).
        q = np.asarray(c["sensor"]["quaternion_xyzw"])
        x, y, z, w = q
        rotation = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                             [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                             [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        np.testing.assert_allclose(candidates[i][:3, :3], rotation, atol=1e-12)
        # Bit for bit: the same grid and the same code, on any number of threads.
        assert plan.gains[i].gain == c["predicted_gain"], i
        assert plan.gains[i].cells == c["predicted_cells"], i
        assert plan.estimated[i] == c.get("estimated", False), i
        assert plan.scores[i] == c["score"], i
        assert c["greedy_gain"] is None  # the swept search computes no greedy reference
    assert plan.greedy_gains == []
    # The default around objects with the robot's pose known (the last cloud's): the surface
    # model ranked by travel, as the CLI's.
    assert (cli["method"], cli["search"]) == ("latombe+surface", plan.search)
    assert plan.search == "swept"
    assert plan.gains[plan.best].gain > 0.0  # the chosen view's bits, predicted in full


def test_evaluate_views_gives_the_plan_gains(planned):
    manifest, candidates, grid, _, _ = planned
    paper = vt.PlannerConfig(method="probabilistic", search="exhaustive")
    plan = vt.plan_next_view(grid, candidates, manifest["fov"], paper)
    gains = vt.evaluate_views(grid, candidates, manifest["fov"])
    assert [g.gain for g in gains] == [g.gain for g in plan.gains]
    assert [g.targets for g in gains] == [g.targets for g in plan.gains]
    one_thread = vt.evaluate_views(grid, candidates, manifest["fov"],
                                   vt.GainConfig(num_threads=1))
    assert [g.gain for g in one_thread] == [g.gain for g in gains]


def test_the_chosen_views_prediction_can_be_left_out(planned):
    # `vantage plan --no-prediction`: the same choice, and no bits predicted for it (the survival
    # reading's, which follow its decision by cells).
    manifest, candidates, grid, _, _ = planned
    config = vt.PlannerConfig(method="survival", predict_chosen=False)
    assert vt.PlannerConfig().predict_chosen and not config.predict_chosen
    full = vt.plan_next_view(grid, candidates, manifest["fov"], vt.PlannerConfig(method="survival"))
    decided = vt.plan_next_view(grid, candidates, manifest["fov"], config)
    assert decided.best == full.best
    assert decided.gains[decided.best].gain == 0.0 and full.gains[full.best].gain > 0.0


def test_travel_needs_the_robot(planned):
    # Without `robot` the default weighs no travel (the surface model alone); a method that weighs
    # travel is refused, naming what is missing; with it, the CLI's default and choice.
    manifest, candidates, grid, plan, cli = planned
    assert vt.PlannerConfig().method == "surface"
    latombe = vt.PlannerConfig(method="latombe+surface")
    with pytest.raises(ValueError, match="robot"):
        vt.plan_next_view(grid, candidates, manifest["fov"], latombe)
    robot = np.eye(4)
    robot[:3, 3] = cli["robot"]["sensor"]["position"]
    weighed = vt.plan_next_view(grid, candidates, manifest["fov"], latombe, robot=robot)
    assert weighed.best == plan.best == cli["next_best_view"]["index"]
