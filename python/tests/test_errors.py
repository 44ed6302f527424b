"""Bad input raises a Python exception with the library's one-line message: ValueError for bad
arguments, OSError for files, never a crash and never a silent default."""

import numpy as np
import pytest

import vantage as vt
from conftest import cli_error

FOV = vt.SensorFov()
SPEC = vt.GridSpec((0, 0, 0), 0.1, (10, 10, 10))


def shear():
    pose = np.eye(4)
    pose[0, 1] = 0.3
    return pose


@pytest.mark.parametrize("points", [
    np.array([[1.0, 0.5, 0.5], [np.nan, 0.5, 0.5]]),
    np.array([[1.0, np.inf, 0.5]]),
])
def test_non_finite_points_raise_and_leave_the_grid(points):
    grid = vt.OccupancyGrid(SPEC)
    with pytest.raises(ValueError, match="is not finite"):
        grid.integrate(points, np.eye(4), FOV)
    assert grid.counts()["unobserved"] == SPEC.num_cells
    mapper = vt.Mapper(SPEC)
    with pytest.raises(ValueError, match="is not finite"):
        mapper.add_scan(points, np.eye(4), FOV)
    assert mapper.scans == 0
    with pytest.raises(ValueError, match=r"clouds\[0\]: .*is not finite"):
        vt.plan([points], np.eye(4)[None], FOV, SPEC, np.eye(4)[None])


@pytest.mark.parametrize("pose, problem", [
    (shear(), "rotation is not orthonormal"),
    (np.diag([1.0, 1.0, -1.0, 1.0]), "reflection"),
    (np.vstack([np.eye(4)[:3], [0, 0, 1, 1]]), "bottom row"),
    (np.full((4, 4), np.nan), "NaN"),
])
def test_non_rigid_poses_raise(pose, problem):
    grid = vt.OccupancyGrid(SPEC)
    with pytest.raises(ValueError, match=f"T_world_sensor is not a rigid transform: .*{problem}"):
        grid.integrate(np.array([[1.0, 0.5, 0.5]]), pose, FOV)
    with pytest.raises(ValueError, match=rf"poses\[1\] is not a rigid transform: .*{problem}"):
        vt.evaluate_views(grid, [np.eye(4), pose], FOV)
    with pytest.raises(ValueError, match=rf"candidates\[0\] is not a rigid transform: .*{problem}"):
        vt.plan_next_view(grid, pose[None], FOV)


@pytest.mark.parametrize("resolution", [0.0, -0.1, float("nan"), float("inf")])
def test_bad_resolution_raises(resolution):
    with pytest.raises(ValueError, match="resolution"):
        vt.GridSpec((0, 0, 0), resolution, (10, 10, 10))
    with pytest.raises(ValueError, match="resolution"):
        vt.grid_for_roi((0, 0, 0), (1, 1, 1), resolution)


def test_bad_shapes_and_names_raise():
    grid = vt.OccupancyGrid(SPEC)
    with pytest.raises(ValueError, match=r"N x 3 .*shape \(4, 2\)"):
        grid.integrate(np.zeros((4, 2)), np.eye(4), FOV)
    with pytest.raises(ValueError, match=r"K x 4 x 4 .*shape \(3, 3\)"):
        vt.evaluate_views(grid, np.eye(3), FOV)
    with pytest.raises(ValueError, match="dims"):
        vt.GridSpec((0, 0, 0), 0.1, (10, 0, 10))
    with pytest.raises(ValueError, match="too many|cells"):
        vt.GridSpec((0, 0, 0), 0.1, (2000, 2000, 2000))
    # issue 53: counts past what a field holds are range errors, not type errors.
    with pytest.raises(ValueError, match=r"dims\[0\] = 2147483648 lies past the 2147483647 cells"):
        vt.GridSpec((0, 0, 0), 0.001, (2**31, 1, 1))
    with pytest.raises(ValueError, match=r"max_memory must be a whole number of bytes in \[0, 2\^64\).*got -1"):
        vt.set_budget(-1)
    with pytest.raises(ValueError, match="unknown gain method 'fancy'"):
        vt.GainConfig(method="fancy")
    with pytest.raises(ValueError, match="epsilon"):
        vt.GainConfig(epsilon=0.7)
    with pytest.raises(ValueError, match="h_fov"):
        vt.SensorFov.from_degrees(190, 40, 0.1, 3)
    with pytest.raises(ValueError, match="frame"):
        vt.plan([], np.zeros((0, 4, 4)), FOV, SPEC, np.eye(4)[None], frame="sideways")
    with pytest.raises(IndexError, match="outside the grid"):
        SPEC.index_of((5.0, 0.5, 0.5))


def test_messages_are_the_clis(vantage_bin):
    with pytest.raises(ValueError) as alpha:
        vt.RayModel(1.5)
    # The CLI refuses --alpha while parsing (a usage error, exit 2), before the library sees it:
    # both lines name the range and the value.
    cli_alpha = cli_error(vantage_bin, "ray", "--alpha", "1.5", "--cells", "0.5")
    for line in (str(alpha.value), cli_alpha):
        assert "alpha" in line and "(0, 1]" in line and "1.5" in line, line
    with pytest.raises(ValueError) as cell:
        vt.RayModel().trace([0.5, 1.2])
    assert str(cell.value) == cli_error(vantage_bin, "ray", "--cells", "0.5,1.2")


def test_missing_files_raise_os_errors(tmp_path, vantage_bin):
    missing = tmp_path / "missing.bt"
    with pytest.raises(FileNotFoundError) as load:
        vt.OccupancyGrid.load(missing)
    assert str(load.value) == cli_error(vantage_bin, "plan", "--map", str(missing))
    for read in (lambda: vt.read_point_cloud(tmp_path / "missing.pcd"),
                 lambda: vt.read_manifest(tmp_path / "missing.yaml"),
                 lambda: vt.Scene(str(tmp_path / "missing.yaml"))):
        with pytest.raises(FileNotFoundError, match="missing"):
            read()
    # A file that exists but is not a map is bad input, a ValueError naming it (as the README
    # says); one that is no file at all (a folder) cannot be read, an OSError.
    bad = tmp_path / "bad.bt"
    bad.write_text("not an octree\n")
    with pytest.raises(ValueError, match="bad.bt"):
        vt.OccupancyGrid.load(bad)
    folder = tmp_path / "folder.bt"
    folder.mkdir()
    with pytest.raises(OSError, match="directory"):
        vt.OccupancyGrid.load(folder)
    folder.rmdir()
    # Writing where no folder can be made is an OSError; nothing is left behind.
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OSError, match="file"):
        vt.OccupancyGrid(SPEC).save(blocker / "map.bt")
    with pytest.raises(OSError):
        vt.write_point_cloud(blocker / "cloud.pcd", np.ones((3, 3)))
    with pytest.raises(ValueError, match=r"\.txt"):
        vt.OccupancyGrid(SPEC).save(tmp_path / "map.txt")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.bt", "file"]


def test_malformed_files_raise_value_errors(tmp_path):
    """Bad input in a file is a ValueError, as a bad argument is (the README), never a
    RuntimeError."""
    cloud = tmp_path / "bad.pcd"
    cloud.write_text("VERSION .7\nFIELDS x y z\nPOINTS lots\n")
    manifest = tmp_path / "manifest.yaml"
    manifest.write_text("clouds: 3\n")
    scene = tmp_path / "scene.yaml"
    scene.write_text("name: [unclosed\n")
    for path, read in ((cloud, vt.read_point_cloud), (manifest, vt.read_manifest),
                       (manifest, vt.map_recorded), (scene, vt.Scene)):
        with pytest.raises(ValueError, match=path.name):
            read(str(path) if read is vt.Scene else path)


HUGE = """
import resource, sys
import vantage as vt
resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
spec = vt.GridSpec((0, 0, 0), 0.01, (1024, 1024, 1024))
try:
    {call}
except MemoryError as e:
    print(e)
    sys.exit(0)
sys.exit("no MemoryError")
"""


@pytest.mark.parametrize("call", ["vt.OccupancyGrid(spec)", "vt.Mapper(spec)"])
def test_a_grid_beyond_the_memory_is_refused_before_it_is_allocated(call):
    """Under a 3 GiB address-space limit a grid of 1024^3 cells (4 GiB of log-odds) is refused
    with the budget's one line, before the allocation would fail."""
    import os
    import subprocess
    import sys
    run = subprocess.run([sys.executable, "-c", HUGE.format(call=call)], capture_output=True,
                         text=True, env=os.environ)
    assert run.returncode == 0, run.stdout + run.stderr
    line = run.stdout.strip()
    assert "1024 x 1024 x 1024 cells needs about" in line, line
    assert "\n" not in line


# issue 39: a call of a wrong type raised pybind11's 3-9 line "incompatible function arguments";
# now one TypeError line naming the argument and the type it must be.
@pytest.mark.parametrize("call, words", [
    (lambda: vt.GridSpec((0, 0, 0), "fine", (10, 10, 10)),
     "GridSpec(): argument 'resolution' must be float, got str"),
    (lambda: vt.OccupancyGrid("spec"),
     "OccupancyGrid(): argument 'spec' must be vantage.GridSpec, got str"),
    (lambda: vt.GridSpec((0, 0, 0), 0.1, (10, 10, 10), bogus=1),
     "GridSpec(): no argument named 'bogus'"),
    (lambda: vt.entropy_bits("half"), "entropy_bits(): argument 'p' must be float, got str"),
    (lambda: vt.ring_candidates(((0, 0, 0), (1, 1, 1)), positions="x"),
     "ring_candidates(): argument 'positions' must be Optional[int], got str"),
    (lambda: vt.read_point_cloud(3), "read_point_cloud(): argument 'path' must be os.PathLike"),
    (lambda: vt.OccupancyGrid(SPEC).integrate(np.ones((1, 3)), np.eye(4), "fov"),
     "OccupancyGrid.integrate(): argument 'fov' must be"),
])
def test_a_wrong_type_is_one_line_naming_the_argument(call, words):
    with pytest.raises(TypeError) as raised:
        call()
    message = str(raised.value)
    assert "\n" not in message, message
    assert words in message, message
    assert "incompatible" not in message, message


# issue 39: the candidate limit is the library's, the same for Python as for `plan --views`.
def test_candidate_counts_beyond_the_limit_are_refused_before_they_are_made():
    with pytest.raises(ValueError, match=r"make 300000 views, more than the 100000"):
        vt.ring_candidates(((0, 0, 0), (1, 1, 1)), positions=100000)
    with pytest.raises(ValueError, match=r"make 300000 views, more than the 100000"):
        vt.ring_poses((0, 0, 0), 1.0, 1.0, 100000)
    with pytest.raises(ValueError, match=r"sphere.views \(200000\) is more than the 100000"):
        vt.sphere_poses((0, 0, 0), 1.0, 200000)


# issue 39: Python honours a user's budget as the CLI's --max-memory and --max-work do, through
# one process-wide setting (vt.set_budget), checked before a grid is allocated or a decision made.
@pytest.fixture
def budget():
    before = vt.budget()
    yield
    vt.set_budget(**before)


def test_a_grid_past_the_users_memory_budget_is_refused(budget):
    spec = vt.GridSpec((0, 0, 0), 0.01, (100, 100, 100))  # 4 MB of log-odds
    vt.set_budget(max_memory=1 << 20)
    with pytest.raises(MemoryError) as refused:
        vt.OccupancyGrid(spec)
    line = str(refused.value)
    assert "100 x 100 x 100 cells needs about" in line and "more than max_memory 1 MiB" in line
    assert "\n" not in line
    vt.set_budget(max_memory=64 << 20)
    assert vt.OccupancyGrid(spec).spec.num_cells == 10**6
    assert vt.budget() == {"max_memory": 64 << 20, "max_work": 60.0}


def test_a_decision_past_the_users_work_budget_is_refused_before_it_runs(budget):
    spec = vt.GridSpec((-0.5, -0.5, 0.5), 0.02, (50, 50, 25))
    grid = vt.OccupancyGrid(spec)
    poses = vt.ring_candidates(spec)
    fov = vt.SensorFov()
    vt.set_budget(max_work=1e-6)
    with pytest.raises(ValueError) as refused:
        vt.plan_next_view(grid, poses, fov, vt.PlannerConfig(method="survival"))
    line = str(refused.value)
    assert "the swept search over 30 views" in line and "more than max_work 1e-06 s" in line
    assert "\n" not in line
    vt.set_budget()
    assert vt.plan_next_view(grid, poses, fov, vt.PlannerConfig(method="survival")).search == "swept"
    with pytest.raises(ValueError, match="max_work must be a positive number of seconds"):
        vt.set_budget(max_work=0)
