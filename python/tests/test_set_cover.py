"""The fewest views (scripts/set_cover.py) on hand-made hit sets: a case where the greedy oracle
takes one view too many, the tour through the chosen views worked out by hand, the full cover, and
random cases (fixed seeds) in which the cover, the branch and bound's answer for each k
(scripts/max_coverage.py), its relaxation and the tabu search are held to the fewest views and the
most cells found by trying every subset."""

import csv
import itertools
import json
import math
import random

import pytest

from conftest import tree_modules


@pytest.fixture(scope="module")
def set_cover(source_dir):
    with tree_modules(source_dir / "scripts", "set_cover") as (module,):
        yield module


def write_truth(folder, scene, views, starts, positions, start_positions):
    """A yardstick file of cells 0..|V|-1, views and starts at positions on a line (travel =
    distance along it)."""
    visible = set().union(*views, *starts)
    truth = {"scene": scene, "candidates": "ring", "surface_cells": len(visible) + 3,
             "visible_cells": len(visible), "views": [sorted(v) for v in views],
             "starts": [sorted(s) for s in starts],
             "travel_m": {"views": [[abs(a - b) for b in positions] for a in positions],
                          "from_starts": [[abs(a - b) for b in positions]
                                          for a in start_positions]}}
    (folder / "yardstick").mkdir(exist_ok=True)
    (folder / "yardstick" / f"{scene}.json").write_text(json.dumps(truth))


def rows(folder):
    with open(folder / "set_cover.csv", newline="") as f:
        return list(csv.DictReader(f))


def test_the_cover_beats_the_greedy_oracle_where_greedy_overlaps(tmp_path, set_cover):
    # V = cells 0..7; the start hits 7. View 0 hits 0..3 (ties with view 2 for the most, and is
    # nearer: greedy's first); then view 2 adds {5, 6} and view 1 {4}: greedy takes 3 views for
    # all 8 cells, the cover 2 (views 1 and 2).
    views = [{0, 1, 2, 3}, {0, 1, 4}, {2, 3, 5, 6}]
    write_truth(tmp_path, "toy", views, [{7}], positions=[1.0, 5.0, 2.0], start_positions=[0.0])
    set_cover.main(["set_cover.py", str(tmp_path), "--levels", "50,100"])
    got = {r["level"]: r for r in rows(tmp_path)}
    # 100 %: all 8 cells.
    assert got["100"]["greedy_views"] == "3"
    assert got["100"]["set_cover_views"] == "2"
    assert got["100"]["views"] == "1 2"
    assert got["100"]["lower_bound"] == "2"
    assert float(got["100"]["gap"]) == 0.0
    assert 0 <= float(got["100"]["cpu_seconds"])
    # The shortest path from 0 through the views at 5 and 2: 0 -> 2 -> 5 = 5 m.
    assert float(got["100"]["tour_m"]) == pytest.approx(5.0)
    assert got["100"]["tour_method"] == "exact"
    # greedy's three views at 1, 2 and 5 m: 5 m too.
    assert float(got["100"]["greedy_tour_m"]) == pytest.approx(5.0)
    # 50 %: 4 cells, the start's 1 and view 0's or view 2's: one view, which no fewer can beat
    # (the counting bound proves it without the solver).
    assert got["50"]["set_cover_views"] == "1"
    assert got["50"]["status"] == "proven"
    assert got["50"]["solver"] == "counting bound"
    # For all 8, two views hit at most 4 + 4 new cells: at least 2, and views 1 and 2 do it.
    assert got["100"]["status"] == "proven"
    truth = set_cover.load_truth(tmp_path / "yardstick" / "toy.json")
    assert set_cover.size_bound(truth, 0, 7) == 2
    assert set_cover.size_bound(truth, 0, 9) == 3
    assert set_cover.size_bound(truth, 0, 12) == 4  # more than all views hit


def test_a_level_no_view_set_reaches_is_said_so(tmp_path, set_cover):
    # Cell 2 is hit only by the second start: from the first, at most 2 of 3 cells.
    write_truth(tmp_path, "toy", [{0}, {1}], [set(), {2}], positions=[0.0, 1.0],
                start_positions=[0.0, 1.0])
    set_cover.main(["set_cover.py", str(tmp_path), "--levels", "60,100"])
    got = {(r["start"], r["level"]): r for r in rows(tmp_path)}
    assert got[("0", "60")]["set_cover_views"] == "2"
    assert got[("0", "100")]["status"] == "not reachable from this start"
    assert got[("0", "100")]["set_cover_views"] == ""
    assert got[("1", "100")]["set_cover_views"] == "2"


@pytest.mark.parametrize("seed", range(6))
def test_random_covers_reach_their_level_with_no_more_views_than_greedy(tmp_path, set_cover,
                                                                         seed):
    rng = random.Random(seed)
    cells = 60
    views = [set(rng.sample(range(cells), rng.randint(3, 15))) for _ in range(14)]
    starts = [set(rng.sample(range(cells), 5))]
    hit = set().union(*views, *starts)
    positions = [rng.uniform(0, 4) for _ in views]
    write_truth(tmp_path, "rand", views, starts, positions, start_positions=[2.0])
    set_cover.main(["set_cover.py", str(tmp_path), "--levels", "80,90,95,99,100"])
    for r in rows(tmp_path):
        need = -(-float(r["level"]) * len(hit) // 100)
        chosen = [int(v) for v in r["views"].split()]
        covered = set(starts[0]).union(*(views[v] for v in chosen))
        assert len(covered) >= need, r
        assert int(r["set_cover_views"]) == len(chosen)
        assert int(r["set_cover_views"]) <= int(r["greedy_views"]), r
        assert int(r["lower_bound"]) <= int(r["set_cover_views"])


@pytest.mark.parametrize("seed", range(8))
def test_the_cover_is_the_fewest_views_every_subset_finds(tmp_path, set_cover, seed):
    # Overlapping views, so that greedy is often one view over: the branch and bound's cover
    # against the smallest subset of the 16 views, found by trying them all.
    rng = random.Random(100 + seed)
    cells = 80
    views = [set(rng.sample(range(cells), rng.randint(8, 30))) for _ in range(16)]
    starts = [set(rng.sample(range(cells), 4))]
    hit = set().union(*views, *starts)
    write_truth(tmp_path, "rand", views, starts, [float(v) for v in range(16)],
                start_positions=[0.0])
    set_cover.main(["set_cover.py", str(tmp_path), "--levels", "80,90,95,99,100"])
    for r in rows(tmp_path):
        need = -(-float(r["level"]) * len(hit) // 100)
        fewest = next(k for k in range(len(views) + 1)
                      if any(len(starts[0].union(*(views[v] for v in subset))) >= need
                             for subset in itertools.combinations(range(len(views)), k)))
        assert int(r["set_cover_views"]) == fewest, r
        assert int(r["lower_bound"]) == fewest, r
        assert float(r["gap"]) == 0.0


def brute_fewest(views, start, need):
    """The fewest views whose hits with `start` reach `need` cells, by trying every subset."""
    return next(k for k in range(len(views) + 1)
                if any(len(start.union(*(views[v] for v in subset))) >= need
                       for subset in itertools.combinations(range(len(views)), k)))


def random_truth(rng, cells, count, low, high):
    views = [set(rng.sample(range(cells), rng.randint(low, high))) for _ in range(count)]
    start = set(rng.sample(range(cells), 4))
    truth = {"scene": "rand", "candidates": "ring", "views": views, "starts": [start],
             "visible_cells": len(start.union(*views))}
    return truth, views, start


def brute_most(views, start, k):
    """The most cells k views hit beyond `start`, by trying every set of k."""
    return max(len(set().union(*(views[v] for v in subset)) - start)
               for subset in itertools.combinations(range(len(views)), k))


@pytest.fixture(scope="module")
def max_coverage(set_cover):
    import max_coverage
    return max_coverage


def answers_as_every_subset(max_coverage, views, start, ks):
    """For each k of `ks`: at the most new cells some k views hit (brute force), the search says
    yes with views that do; one cell more, no."""
    cells = max_coverage.Cells(views, start)
    for k in ks:
        most = brute_most(views, start, k)
        found = max_coverage.Search(cells, most, math.inf).reach(k)
        assert found is not None and len(found) <= k, (k, most)
        chosen = [int(cells.views[j]) for j in found]
        assert len(set().union(*(views[v] for v in chosen)) - start) >= most
        assert max_coverage.Search(cells, most + 1, math.inf).reach(k) is None, (k, most)


@pytest.mark.parametrize("seed", range(10))
def test_the_search_answers_as_every_subset_does(max_coverage, seed):
    # Do k views hit `need` new cells? At the most cells some k views hit, yes (and the views it
    # gives do); one cell more, no: the branch and bound against every subset, k = 1..4.
    rng = random.Random(200 + seed)
    truth, views, start = random_truth(rng, 60, 12, 5, 20)
    answers_as_every_subset(max_coverage, views, start, range(1, 5))


@pytest.mark.parametrize("seed", range(6))
def test_the_search_answers_as_every_subset_does_deeper(max_coverage, seed):
    # The same at k = 5 and 6 of 14 views, where the search branches below the root, takes the
    # views whose leaving out refutes and tries two views left exactly.
    rng = random.Random(500 + seed)
    truth, views, start = random_truth(rng, 70, 14, 4, 14)
    answers_as_every_subset(max_coverage, views, start, (5, 6))


@pytest.mark.parametrize("seed", range(6))
def test_the_relaxation_bounds_every_subset_from_above(max_coverage, seed):
    rng = random.Random(300 + seed)
    truth, views, start = random_truth(rng, 50, 12, 4, 16)
    cells = max_coverage.Cells(views, start)
    for k in range(1, 5):
        assert max_coverage.relaxation_bound(cells, 0, k) >= brute_most(views, start, k) - 1e-6
    # Every view: every new cell.
    everything = len(set().union(*views) - start)
    assert max_coverage.relaxation_bound(cells, 0, len(cells.views)) == pytest.approx(everything)


@pytest.mark.parametrize("seed", range(6))
def test_the_tabu_search_never_claims_a_cover_it_lacks(max_coverage, seed):
    rng = random.Random(400 + seed)
    truth, views, start = random_truth(rng, 50, 12, 4, 16)
    cells = max_coverage.Cells(views, start)
    for k in range(1, 5):
        most = brute_most(views, start, k)
        for need in (most, most + 1):
            found = max_coverage.tabu(cells, k, need, [], math.inf)
            if need > most:
                assert found is None
            elif found is not None:
                chosen = [int(cells.views[j]) for j in found]
                assert len(chosen) == k
                assert len(set().union(*(views[v] for v in chosen)) - start) >= need


def test_a_view_within_another_is_dropped_and_equal_ones_keep_the_first(max_coverage):
    # Beyond the start's cell 9: view 1's cells lie in view 0's; views 2 and 3 hit the same new
    # cells (3 also hits the start's); view 4 hits one cell no other does.
    views = [{0, 1, 2}, {1, 2}, {3, 4}, {3, 4, 9}, {5}]
    cells = max_coverage.Cells(views, {9})
    assert cells.views.tolist() == [0, 2, 4]
    # Groups by the views that hit them: {0} (view 0), {1, 2} (views 0, 1), {3, 4}, {5}.
    assert sorted(cells.weight.tolist()) == [1, 1, 2, 2]
    assert cells.covered([0, 1]) == 5  # columns 0 and 1: views 0 and 2


def test_the_full_cover_counts_what_the_start_and_the_candidates_hit(tmp_path, set_cover):
    # Cell 3 is hit only by the second start: the full cover from the first is cells 0-2,
    # needing both views (view 1 alone hits cell 2), and from the second all four cells, needing
    # view 1 alone (the start hits 0, 1 and 3).
    write_truth(tmp_path, "toy", [{0, 1}, {2}], [{0}, {0, 1, 3}], positions=[0.0, 1.0],
                start_positions=[0.0, 1.0])
    set_cover.main(["set_cover.py", str(tmp_path), "--levels", "full,100"])
    got = {(r["start"], r["level"]): r for r in rows(tmp_path)}
    assert got[("0", "full")]["need_cells"] == "3"
    assert got[("0", "full")]["set_cover_views"] == "2"
    assert got[("0", "100")]["status"] == "not reachable from this start"
    assert got[("1", "full")]["need_cells"] == "4"
    assert got[("1", "full")]["set_cover_views"] == "1"
    assert got[("1", "full")]["views"] == "1"
    assert got[("1", "full")]["status"] == "proven"


def test_the_summary_divides_each_trials_views_by_the_fewest(plot_bench):
    # Scene s, 2 starts: trials 0 and 2 start from start 0 (fewest 2 views to 80 %), trial 1
    # from start 1 (fewest 4). Greedy reaches 80 % at scans 3, 5 and never (budget 6).
    cover = [{"scene": "s", "start": "0", "level": "80", "set_cover_views": "2",
              "greedy_views": "3", "status": "proven"},
             {"scene": "s", "start": "1", "level": "80", "set_cover_views": "4",
              "greedy_views": "4", "status": "time limit"}]
    levels = plot_bench.SURFACE_LEVELS

    def trial(number, to80):
        m = {"scene": "s", "method": "greedy", "setting": ("", ""), "trial": str(number)}
        m.update({("scans_to", lv): None for lv in levels})
        m[("scans_to", 0.80)] = to80
        return m

    lines = plot_bench.optimum_ratios([trial(0, 3), trial(1, 5), trial(2, None)], 6, cover,
                                      {"s": 2})
    row = next(line for line in lines if line.startswith("| greedy |"))
    # (3 - 1) / 2 = 1, (5 - 1) / 4 = 1, censored (6 - 1) / 2 = 2.5: mean 1.5.
    assert row == "| greedy | 1.50 (1/3 cens.) |"
    oracle = next(line for line in lines if line.startswith("| greedy oracle"))
    # 3 / 2 and 4 / 4: mean 1.25; one of the two optima proven.
    assert oracle == "| greedy oracle, true hit sets | 1.25 (1/2 proven) |"


def test_the_summary_gives_the_same_ratios_by_the_truth(plot_bench):
    cover = [{"scene": "s", "start": "0", "level": "80", "set_cover_views": "2",
              "greedy_views": "2", "status": "proven"}]
    m = {"scene": "s", "method": "greedy", "setting": ("", ""), "trial": "0"}
    m.update({("scans_to", lv): None for lv in plot_bench.SURFACE_LEVELS})
    m[("scans_to", 0.80)] = 2  # by the registered points: 1 view, half the fewest
    truth = {"label": "greedy", "scene": "s", "trial": 0}
    truth.update({lv: 7 for lv in plot_bench.SURFACE_LEVELS})  # 7 = budget + 1: never
    truth[0.80] = 4  # by the truth: 3 views
    lines = plot_bench.optimum_ratios([m], 6, cover, {"s": 1}, [truth])
    row = next(line for line in lines if line.startswith("| greedy |"))
    assert row == "| greedy | 0.50 (0/1 cens.) | 1.50 (0/1 cens.) |"
    oracle = next(line for line in lines if line.startswith("| greedy oracle"))
    assert oracle == "| greedy oracle, true hit sets | - | 1.00 (1/1 proven) |"
