"""The simulator through the bindings: built-in scenes, and scans that lie where the sensor can
see and repeat for a seed on any number of threads."""

import numpy as np
import pytest

import vantage as vt


@pytest.fixture(scope="module")
def world():
    return vt.World("tabletop-1")


def test_builtin_scenes_load_by_name():
    names = vt.builtin_scene_names()
    assert "tabletop-1" in names and "office-small-sparse" in names
    scene = vt.Scene("tabletop-1")
    assert scene.name == "tabletop-1" and scene.kind == "tabletop"
    assert scene.source == "built-in"
    assert scene.start_poses.shape[1:] == (4, 4) and len(scene.start_poses) > 0
    assert scene.candidate_poses().shape == (30, 4, 4)  # the paper's ring, 10 x 3
    assert vt.Scene("office-small-sparse").kind == "office"


def test_scan_points_lie_in_the_field_of_view(world):
    scene = world.scene
    pose = scene.start_poses[0]
    points = world.scan(pose, seed=1)
    assert points.ndim == 2 and points.shape[1] == 3 and len(points) > 1000
    assert np.all(np.isfinite(points))
    fov = scene.fov
    r = np.linalg.norm(points, axis=1)
    assert np.all((r >= fov.min_range - 1e-9) & (r <= fov.max_range + 1e-9))
    x, y, z = points.T
    assert np.all(x > 0)
    assert np.all(np.abs(y) <= x * np.tan(fov.h_fov / 2) + 1e-9)
    assert np.all(np.abs(z) <= x * np.tan(fov.v_fov / 2) + 1e-9)
    # frame='world' is the same scan through the pose (the table tops have no pose noise).
    in_world = world.scan(pose, seed=1, frame="world")
    np.testing.assert_allclose(in_world, points @ pose[:3, :3].T + pose[:3, 3], atol=1e-12)
    np.testing.assert_array_equal(world.noisy_pose(pose, seed=1), pose)


def test_a_seed_gives_the_same_scan_on_any_thread_count(world):
    pose = world.scene.candidate_poses()[4]
    one = vt.World("tabletop-1", num_threads=1).scan(pose, seed=5)
    np.testing.assert_array_equal(world.scan(pose, seed=5), one)
    assert not np.array_equal(world.scan(pose, seed=6), one)  # the range noise moves


def test_scans_map_and_plan(world):
    # The loop of `vantage explore`, one step: scan, map, choose the next view.
    scene = world.scene
    mapper = vt.Mapper(scene.grid, table_segmentation=True)
    pose = scene.start_poses[0]
    update = mapper.add_scan(world.scan(pose), pose, scene.fov)
    assert update.points > 0 and 0 < update.object_points < update.points
    grid = mapper.grid
    assert update.integration.left_unobserved == grid.spec.num_cells - grid.counts()["unobserved"]
    plan = vt.plan_next_view(grid, scene.candidate_poses(), scene.fov)
    assert plan.gains[plan.best].gain > 0.0


def test_pose_from_xyz_rpy_matches_look_at():
    # Yaw 90 degrees at the origin looks along +y, as look_at((0, 0, 0), (0, 1, 0)) does.
    pose = vt.pose_from_xyz_rpy((0, 0, 0), (0, 0, np.pi / 2))
    np.testing.assert_allclose(pose, vt.look_at((0, 0, 0), (0, 1, 0)), atol=1e-12)


def test_an_object_sits_on_its_view_sphere():
    scene = vt.object_scene("bunny")
    assert scene.kind == "object" and scene.name == "bunny"
    views = scene.candidate_poses()
    assert views.shape == (32, 4, 4)
    center = views[:, :3, 3].mean(axis=0)
    assert np.allclose(np.linalg.norm(views[:, :3, 3] - center, axis=1), 0.7, atol=0.02)
    # The starts are the sphere's views, in another order.
    assert len(scene.start_poses) == 32
    wider = vt.object_scene("bunny", views=40, view_radius=1.0)
    assert len(wider.candidate_poses()) == 40
    with pytest.raises(ValueError, match="minimum range"):
        vt.object_scene("bunny", view_radius=0.3)


def test_candidate_sets_come_from_one_registry():
    names = [name for name, _ in vt.candidate_sets()]
    assert names[:4] == ["ring", "hemisphere", "sphere", "view-sphere"]
    assert "frontier" in names and "stops" in names and "file" in names
    views = vt.candidate_views("view-sphere", [-0.1, -0.1, -0.1], [0.1, 0.1, 0.1], radius=0.7)
    assert views.shape == (32, 4, 4)
    assert np.allclose(np.linalg.norm(views[:, :3, 3], axis=1), 0.7)
    ring = vt.candidate_views("ring", [-0.5, -0.5, 0.75], [0.5, 0.5, 1.0])
    assert ring.shape == (30, 4, 4)
    with pytest.raises(ValueError, match="unknown candidate set 'cube'"):
        vt.candidate_views("cube", [0, 0, 0], [1, 1, 1])
    with pytest.raises(ValueError, match="found in a map"):
        vt.candidate_views("frontier", [0, 0, 0], [1, 1, 1])
    with pytest.raises(ValueError, match="an office robot's"):
        vt.candidate_views("stops", [0, 0, 0], [1, 1, 1])
