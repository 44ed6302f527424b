"""The parts of scripts/gap_by_cell_state.py (issue 51) on hand-made hit sets and grids: the new
cells of each view and the greedy oracle's pick with its ties, each cell's kind by the map's
state, log-odds and Chebyshev distance, the planner's rank of a view, and the scan groups."""

import math

import numpy as np
import pytest

from conftest import tree_modules

UNOBSERVED, FREE, OCCUPIED = 0, 1, 2


@pytest.fixture(scope="module")
def gap(source_dir):
    with tree_modules(source_dir / "scripts", "gap_by_cell_state") as (module,):
        yield module


def test_the_best_view_has_most_new_cells_then_the_shorter_travel_then_the_lower_index(gap):
    views = [np.array([0, 1, 2], np.uint32), np.array([2, 3, 4], np.uint32),
             np.array([1, 5], np.uint32), np.array([3, 4, 6], np.uint32)]
    hit = np.zeros(8, bool)
    hit[[2, 5]] = True
    fresh = gap.new_cells(views, hit, [0, 1, 2, 3])
    assert [fresh[c].tolist() for c in range(4)] == [[0, 1], [3, 4], [1], [3, 4, 6]]
    assert gap.best_view(fresh, np.array([1.0, 1.0, 1.0, 2.0])) == 3
    # Without view 3: views 0 and 1 tie at 2 new cells; the shorter travel, then the lower index.
    del fresh[3]
    assert gap.best_view(fresh, np.array([1.0, 0.5, 0.1, 0.0])) == 1
    assert gap.best_view(fresh, np.array([0.5, 0.5, 0.1, 0.0])) == 0


def test_each_cell_is_sorted_by_what_the_map_holds(gap):
    cells = np.full((5, 1, 1), UNOBSERVED, np.uint8)
    log_odds = np.zeros((5, 1, 1), np.float32)
    cells[0, 0, 0], log_odds[0, 0, 0] = OCCUPIED, gap.HIT            # one hit
    cells[1, 0, 0], log_odds[1, 0, 0] = OCCUPIED, 2 * gap.HIT + math.log(0.4 / 0.6)  # net 1.3
    cells[2, 0, 0], log_odds[2, 0, 0] = FREE, math.log(0.4 / 0.6)
    # Along x: occupied by one hit, occupied by two hits and a miss, free, then two unobserved
    # cells 2 and 3 cells from the nearest occupied one: farther than one cell, both.
    distance = gap.distance_to_occupied(cells)
    assert distance.tolist() == [0, 0, 1, 2, 3]
    k = gap.kinds(np.arange(5), cells, log_odds, distance)
    assert [k[kind] for kind in gap.KINDS] == [1, 1, 0, 1, 0, 2]
    three = np.full((1, 1, 1), OCCUPIED, np.uint8)
    k = gap.kinds(np.array([0]), three, np.full((1, 1, 1), 3.0, np.float32),
                  gap.distance_to_occupied(three))
    assert k[gap.KINDS[2]] == 1
    # Chebyshev: a diagonal neighbour is one cell away; a map with nothing occupied, far.
    grid = np.full((3, 3, 3), UNOBSERVED, np.uint8)
    grid[0, 0, 0] = OCCUPIED
    assert gap.distance_to_occupied(grid)[13] == 1  # [1, 1, 1], x fastest
    k = gap.kinds(np.array([13, 26]), grid, np.zeros(grid.shape, np.float32),
                  gap.distance_to_occupied(grid))
    assert k[gap.KINDS[4]] == 1 and k[gap.KINDS[5]] == 1
    assert gap.distance_to_occupied(np.zeros((2, 2, 2), np.uint8)).min() > 1000


def test_the_rank_follows_the_planners_ranking(gap):
    gains = np.array([10.0, 8.0, 6.0, np.nan])
    travel = np.array([2.0, 0.0, 0.0, 0.0])
    # By the gain alone view 2 is behind views 0 and 1; by travel (e^-1 halves view 0's
    # 10 to 3.7) only behind view 1. The taken view 3 (NaN) is not open.
    assert gap.rank(gains, travel, 2, [0, 1, 2], by_travel=False) == 2
    assert gap.rank(gains, travel, 2, [0, 1, 2], by_travel=True) == 1


def test_decisions_are_grouped_by_the_scan_they_choose(gap):
    assert [gap.phase(s) for s in (2, 4, 5, 7, 8, 14, 30)] == [0, 0, 1, 1, 2, 2, 2]
