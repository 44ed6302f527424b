"""ExploreEnv and bench_policy (python/vantage/env.py): the loop of `vantage explore` a scan at a
time with the Gymnasium API, and a Python policy's trials in `vantage bench`'s sweep. On the
small test table top (tests/experiment/small_tabletop.yaml), 30 ring views, 32 x 32 x 17 cells."""

import csv
import json
import subprocess
import sys

import numpy as np
import pytest

import vantage as vt

from conftest import tree_modules

TIMES = {"plan_seconds", "register_seconds", "segment_seconds", "integrate_seconds",
         "reference_seconds"}


@pytest.fixture(scope="module")
def scene(source_dir):
    return str(source_dir / "tests" / "experiment" / "small_tabletop.yaml")


@pytest.fixture(scope="module")
def numpy_greedy(source_dir):
    """examples/python/greedy_policy.py as a module."""
    with tree_modules(source_dir / "examples" / "python", "greedy_policy") as (module,):
        yield module


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def episode(env, policy, seed=None):
    """(obs, info) of every state and the rewards of one episode under `policy`."""
    obs, info = env.reset(seed=seed)
    states, rewards, done = [(obs, info)], [], False
    while not done:
        obs, reward, done, truncated, info = env.step(policy(obs))
        assert truncated is False
        states.append((obs, info))
        rewards.append(reward)
    return states, rewards


def test_observation_says_what_a_planner_may_know(scene):
    env = vt.ExploreEnv(scene, scans=3, seed=1)
    assert env.action_space.n == 30 and env.candidates.shape == (30, 4, 4)
    obs, info = env.reset()
    assert obs["cells"].dtype == np.uint8 and obs["cells"].shape == (32, 32, 17)
    assert set(np.unique(obs["cells"])) <= {vt.UNOBSERVED, vt.FREE, vt.OCCUPIED}
    assert (obs["cells"] == vt.OCCUPIED).any() and (obs["cells"] == vt.UNOBSERVED).any()
    assert obs["pose"].shape == (4, 4) and obs["candidates"].shape == (30, 4, 4)
    # The start is ring view 1 (position 0, no yaw offset), taken; travel to it is 0.
    assert obs["taken"].dtype == bool and np.flatnonzero(obs["taken"]).tolist() == [1]
    assert np.allclose(obs["pose"], obs["candidates"][1]) and obs["travel"][1] == 0.0
    assert obs["scan"] == 1 and info["scan"] == 1 and info["view"] == 1
    assert 0.0 < info["surface_coverage"] < 1.0 and info["plan_seconds"] == 0.0
    obs, reward, terminated, truncated, info = env.step(np.int64(15))
    assert obs["taken"][15] and obs["scan"] == 2 and not terminated and not truncated
    assert info["view"] == 15 and info["travel_m"] > 0.0 and info["plan_seconds"] >= 0.0
    assert reward >= 0.0
    obs, reward, terminated, truncated, info = env.step(7)
    assert terminated and info["stop_reason"] == "took every scan asked for"


def test_the_same_seed_gives_the_same_episode(scene):
    env = vt.ExploreEnv(scene, scans=4, seed=5)
    first, rewards = episode(env, vt.random_policy(seed=2))
    again, rewards_again = episode(vt.ExploreEnv(scene, scans=4), vt.random_policy(seed=2),
                                   seed=5)
    assert rewards == rewards_again
    for (obs, info), (obs2, info2) in zip(first, again):
        assert np.array_equal(obs["cells"], obs2["cells"]) and info["view"] == info2["view"]
        assert info["surface_coverage"] == info2["surface_coverage"]
    # Another seed, the same views: other sensor noise, another map.
    other, _ = episode(env, lambda obs: [None, 3, 9, 21][obs["scan"]], seed=6)
    same_views, _ = episode(env, lambda obs: [None, 3, 9, 21][obs["scan"]], seed=5)
    assert not np.array_equal(other[-1][0]["cells"], same_views[-1][0]["cells"])
    # reset() without a seed moves on to the next one.
    env.reset(seed=9)
    env.reset()
    assert env.seed == 10


def test_reward_is_the_increase_of_surface_coverage(scene):
    states, rewards = episode(vt.ExploreEnv(scene, scans=5, seed=1), vt.random_policy(seed=1))
    coverage = [info["surface_coverage"] for _, info in states]
    assert rewards == pytest.approx(np.diff(coverage).tolist(), abs=1e-15)
    assert sum(rewards) == pytest.approx(coverage[-1] - coverage[0])


def test_following_the_reference_is_the_bench_trial_of_that_method(scene, vantage_bin,
                                                                   tmp_path):
    """The env's loop and seeds are the bench's: taking the built-in greedy's choices gives
    greedy's trial of `vantage bench` row for row (besides its predictions and times)."""
    env = vt.ExploreEnv(scene, scans=5, seed=3, start=1, reference="greedy")
    obs, info = env.reset()
    states = [info]
    while "reference" in info:
        obs, _, done, _, info = env.step(info["reference"]["view"])
        states.append(info)
    out = tmp_path / "bench"
    subprocess.run([str(vantage_bin), "bench", "tabletop", "--scenes", scene, "--methods",
                    "greedy", "--trials", "2", "--scans", "5", "--seed", "3", "--out", str(out),
                    "--no-plots"], check=True, capture_output=True)
    rows = [r for r in read_rows(out / "scans.csv") if r["trial"] == "1"]
    assert [int(r["view"]) for r in rows] == [info["view"] for info in states]
    for r, info in zip(rows, states):
        for column in ("surface_coverage", "raw_surface_coverage", "coverage"):
            assert float(r[column]) == pytest.approx(info[column], rel=1e-12), column
        assert int(r["unobserved"]) == info["unobserved"]
        assert float(r["travel_m"]) == pytest.approx(info["travel_m"], abs=1e-9)
    # The env's truth is the sweep's yardstick file (docs/yardstick.md), whose hit sets index V.
    truth = env.truth
    with open(out / "yardstick" / f"{env.scene.name}.json") as f:
        written = json.load(f)
    surface, visible = truth["surface"], truth["visible"]
    assert (len(surface), len(visible)) == (written["surface_cells"], written["visible_cells"])
    assert truth["tolerance_cells"] == written["tolerance_cells"]
    assert np.all(np.diff(surface.astype(np.int64)) > 0) and np.isin(visible, surface).all()
    position = {int(c): k for k, c in enumerate(visible)}
    for mine, theirs in ((truth["views"], written["views"]), (truth["starts"], written["starts"])):
        assert [[position[int(c)] for c in cells] for cells in mine] == theirs
    every = np.unique(np.concatenate(truth["views"] + truth["starts"]))
    assert np.array_equal(every, visible)
    # Surface cells lie on the object: the map's last state has some of them occupied, and the
    # log-odds say the classes the cells say.
    cells, log_odds = obs["cells"], obs["log_odds"]
    assert log_odds.shape == cells.shape and log_odds.dtype == np.float32
    assert (log_odds[cells == vt.OCCUPIED] > 0).all() and (log_odds[cells == vt.FREE] < 0).all()
    assert (log_odds[cells == vt.UNOBSERVED] == 0).all()
    on_surface = cells.ravel(order="F")[surface]
    assert (on_surface == vt.OCCUPIED).mean() > 0.3


@pytest.fixture(scope="module")
def truth_labels(source_dir):
    """examples/python/truth_labels.py as a module."""
    with tree_modules(source_dir / "examples" / "python", "truth_labels") as (module,):
        yield module


def test_following_the_truths_labels_is_the_benchs_greedy_oracle(scene, vantage_bin, tmp_path,
                                                                 truth_labels):
    """examples/python/truth_labels.py's labels, each candidate's new true cells, taken largest
    first (ties to the shorter travel, then the lower index), give the greedy oracle's trial of
    `vantage bench` view for view, and its own count of new cells for the view taken."""
    env = vt.ExploreEnv(scene, scans=6, seed=3, start=1)
    states = truth_labels.episode(
        env, 1, 3, lambda obs, info, labels: truth_labels.oracle_choice(labels, obs["travel"]))
    views = [truth_labels.oracle_choice(labels, travel) for _, _, travel, labels in states]
    out = tmp_path / "bench"
    subprocess.run([str(vantage_bin), "bench", "tabletop", "--scenes", scene, "--methods",
                    "greedy-oracle", "--trials", "2", "--scans", "6", "--seed", "3", "--out",
                    str(out), "--no-plots"], check=True, capture_output=True)
    rows = [r for r in read_rows(out / "scans.csv") if r["trial"] == "1"][1:]
    assert [int(r["view"]) for r in rows] == views
    assert [float(r["predicted_gain"]) for r in rows] == [labels[v] for (_, _, _, labels), v
                                                          in zip(states, views)]
    # Taken views are labelled -1, and a label never grows as views are taken.
    for (_, taken, _, labels), (_, _, _, after) in zip(states, states[1:]):
        assert (labels[taken] == -1).all() and (after[~taken] <= labels[~taken]).all()


def test_the_numpy_greedy_makes_the_builtin_greedys_choices(scene, numpy_greedy):
    """examples/python/greedy_policy.py on the states of two random episodes (12 decisions)."""
    env = vt.ExploreEnv(scene, scans=7, seed=1, reference="greedy")
    policy = numpy_greedy.greedy_policy(env.grid, env.fov)
    checked = 0
    for seed in (1, 2):
        random = vt.random_policy(seed=seed)
        obs, info = env.reset(seed=seed)
        done = False
        while not done:
            assert policy(obs) == info["reference"]["view"], (seed, obs["scan"])
            checked += 1
            obs, _, done, _, info = env.step(random(obs))
    assert checked == 12


def one_line_error(kind, call):
    with pytest.raises(kind) as error:
        call()
    assert "\n" not in str(error.value)
    return str(error.value)


def test_bad_actions_get_one_clear_error(scene):
    env = vt.ExploreEnv(scene, scans=2, seed=1)
    assert "reset()" in one_line_error(RuntimeError, lambda: env.step(2))
    env.reset()
    assert "view 30 is out of range" in one_line_error(ValueError, lambda: env.step(30))
    assert "view -1 is out of range" in one_line_error(ValueError, lambda: env.step(-1))
    assert "view 1 has been taken already" in one_line_error(ValueError, lambda: env.step(1))
    assert "1.5" in one_line_error(ValueError, lambda: env.step(1.5))
    assert "True" in one_line_error(ValueError, lambda: env.step(True))
    assert "'2'" in one_line_error(ValueError, lambda: env.step("2"))
    env.step(2)
    assert "the episode is over" in one_line_error(ValueError, lambda: env.step(3))
    assert "start 10 is out of range" in one_line_error(
        ValueError, lambda: vt.ExploreEnv(scene, start=10))
    assert "unknown method 'greed'" in one_line_error(
        ValueError, lambda: vt.ExploreEnv(scene, reference="greed"))
    assert "office" in one_line_error(ValueError, lambda: vt.ExploreEnv("office-small-sparse"))


def test_a_policy_benched_lands_beside_the_methods(scene, vantage_bin, numpy_greedy, tmp_path,
                                                   plot_bench):
    """bench_policy writes `vantage bench`'s columns with the trials' seeds: the numpy greedy's
    rows are the built-in greedy's (it makes the same choices), into the same folder, and the
    summary compares the policies with the methods."""
    out = tmp_path / "sweep"
    common = ["--scenes", scene, "--trials", "2", "--scans", "4", "--out", str(out), "--no-plots"]
    subprocess.run([str(vantage_bin), "bench", "tabletop", "--methods", "greedy,greedy-oracle",
                    *common], check=True, capture_output=True)
    env = vt.ExploreEnv(scene)
    greedy = numpy_greedy.greedy_policy(env.grid, env.fov)
    assert vt.bench_policy(greedy, [scene], trials=2, scans=4, out=out) == 2
    assert vt.bench_policy(vt.random_policy(seed=0), scene, trials=2, scans=4, out=out) == 2
    assert vt.bench_policy(greedy, [scene], trials=2, scans=4, out=out) == 0  # resumed
    with open(out / "scans.csv") as f:
        header = f.readline().strip()
    assert header == ",".join(read_rows(out / "scans.csv")[0].keys())
    rows = read_rows(out / "scans.csv")
    by = {}
    for r in rows:
        by.setdefault(r["method"], []).append(r)
    assert sorted(by) == ["greedy", "greedy-oracle", "numpy-greedy", "random-policy"]
    assert len(by["numpy-greedy"]) == len(by["greedy"]) == 8
    own = {"method", "predicted_gain", "greedy_predicted_gain", "predicted_cells"} | TIMES
    for mine, builtin in zip(by["numpy-greedy"], by["greedy"]):
        assert {k: v for k, v in mine.items() if k not in own} == {
            k: v for k, v in builtin.items() if k not in own}
        assert mine["predicted_gain"] == "" and mine["alpha"] == ""
    # The summary of plot_bench.py takes the policies as methods beside greedy.
    subprocess.run([sys.executable, str(plot_bench.__file__), str(out)], check=True,
                   capture_output=True)
    summary = (out / "summary.md").read_text()
    assert "numpy-greedy" in summary and "random-policy" in summary


def test_a_bad_policy_stops_the_sweep_and_leaves_no_partial_results(scene, tmp_path):
    def raises(obs):
        if obs["scan"] == 2:
            raise KeyError("no such\nkey")
        return int(np.flatnonzero(~obs["taken"])[0])

    out = tmp_path / "sweep"
    message = one_line_error(RuntimeError, lambda: vt.bench_policy(
        raises, [scene], trials=2, scans=3, out=out, name="raises"))
    assert message.startswith("trial small-tabletop__raises__t0: policy 'raises' raised KeyError")
    assert not (out / "scans.csv").exists() and not list((out / "trials").iterdir())
    for returned, says in ((1.5, "returned 1.5, not a candidate's index"),
                           (1, "view 1 has been taken already"),
                           (99, "view 99 is out of range"),
                           (None, "returned None")):
        message = one_line_error(ValueError, lambda: vt.bench_policy(
            lambda obs: returned, [scene], trials=1, scans=3, out=out, name="bad"))
        assert message.startswith("trial small-tabletop__bad__t0: ") and says in message
    assert not (out / "scans.csv").exists() and not list((out / "trials").iterdir())
    assert "built-in method" in one_line_error(ValueError, lambda: vt.bench_policy(
        raises, [scene], out=out, name="greedy"))
