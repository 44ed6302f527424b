"""The set-cover bound (scripts/set_cover.py) on hand-made hit sets: a case where the greedy
oracle takes one view too many, the tour through the chosen views worked out by hand, and random
cases in which the cover reaches its level and never uses more views than the greedy oracle."""

import csv
import itertools
import json
import random
import sys

import pytest


@pytest.fixture(scope="module")
def set_cover(source_dir):
    sys.path.insert(0, str(source_dir / "scripts"))
    import set_cover
    yield set_cover
    sys.path.remove(str(source_dir / "scripts"))


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
    # The shortest path from 0 through the views at 5 and 2: 0 -> 2 -> 5 = 5 m.
    assert float(got["100"]["tour_m"]) == pytest.approx(5.0)
    assert got["100"]["tour_method"] == "exact"
    # greedy's three views at 1, 2 and 5 m: 5 m too.
    assert float(got["100"]["greedy_tour_m"]) == pytest.approx(5.0)
    # 50 %: 4 cells, the start's 1 and view 0's or view 2's: one view, which no fewer can beat
    # (the counting bound proves it without the solver).
    assert got["50"]["set_cover_views"] == "1"
    assert got["50"]["status"] == "optimal (counting bound)"
    # For all 8, two views hit at most 4 + 4 new cells: at least 2, and views 1 and 2 do it.
    assert got["100"]["status"] == "optimal (branch and bound)"
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
