"""The features and fits of scripts/surface_features.py (issue 51, item 1) on hand-made grids and
counts: each feature worked out by hand, a class's rate with its prior, and a held-out log
likelihood that is higher for the feature that separates the outcomes."""

import math

import numpy as np
import pytest

from conftest import tree_modules

UNOBSERVED, FREE, OCCUPIED = 0, 1, 2


@pytest.fixture(scope="module")
def sf(source_dir):
    with tree_modules(source_dir / "scripts", "surface_features") as (module,):
        yield module


def test_each_feature_of_a_hand_made_grid(sf):
    cells = np.full((9, 9, 50), UNOBSERVED, np.uint8)
    cells[4, 4, 10] = OCCUPIED
    cells[4, 5, 10] = FREE
    cells[5, 4, 10] = FREE
    f = sf.features(cells)
    # distance classes: within 1, 2 (sqrt 2), 3, 4 cells, farther
    assert f["d"][4, 4, 11] == 0 and f["d"][5, 5, 10] == 1 and f["d"][4, 4, 13] == 2
    assert f["d"][4, 4, 14] == 3 and f["d"][4, 4, 15] == 4 and f["d"][4, 4, 10] == 0
    # the cell between the two free ones has both as face neighbours; the grid's edge adds none
    assert f["free"][5, 5, 10] == 2 and f["free"][0, 0, 0] == 0 and f["free"][3, 4, 10] == 0
    # unobserved among 26: all but the occupied one and two free ones next to (4, 4, 11)
    assert f["unobs"][4, 4, 11] == 2  # 23 of 26: 16-23
    assert f["unobs"][4, 4, 30] == 3  # 26 of 26
    assert f["unobs"][0, 0, 0] == 0   # a corner has 7
    # layers above the floor: < 2, < 8, < 20, < 40, more
    assert [f["height"][0, 0, z] for z in (1, 2, 7, 8, 19, 20, 39, 40)] == [0, 1, 1, 2, 2, 3, 3, 4]
    # an occupied cell within 4 straight below / above
    assert f["below"][4, 4, 14] == 1 and f["below"][4, 4, 15] == 0 and f["below"][4, 4, 9] == 0
    assert f["above"][4, 4, 6] == 1 and f["above"][4, 4, 5] == 0 and f["above"][4, 4, 11] == 0


def key(d=0, free=0, unobs=0, height=0, below=0, above=0, occupied=0):
    return (d, free, unobs, height, below, above, occupied)


def test_a_class_rate_is_its_share_pulled_to_the_pooled_rate(sf):
    counts = {key(free=0, occupied=1): 80, key(free=0): 20, key(free=3, occupied=1): 20,
              key(free=3): 80, key(d=4, occupied=1): 1000}  # the far class is left out
    fitted, pooled = sf.rates(counts, ("d", "free"), prior=0.0)
    assert pooled == pytest.approx(0.5)
    assert fitted[(0, 0)] == pytest.approx(0.8) and fitted[(0, 3)] == pytest.approx(0.2)
    fitted, _ = sf.rates(counts, ("d", "free"), prior=100.0)
    assert fitted[(0, 0)] == pytest.approx((80 + 50) / 200)


def test_the_separating_feature_scores_higher_on_held_out_counts(sf):
    fit = {key(free=0, occupied=1): 90, key(free=0): 10, key(free=3, occupied=1): 10,
           key(free=3): 90}
    judge = {key(free=0, occupied=1): 9, key(free=0): 1, key(free=3, occupied=1): 1,
             key(free=3): 9}
    scores = {}
    for names in (("d",), ("d", "free")):
        fitted, pooled = sf.rates(fit, names, prior=0.0)
        scores[names] = sf.log_likelihood(judge, names, fitted, pooled)
    assert scores[("d",)] == pytest.approx(math.log(0.5))
    assert scores[("d", "free")] == pytest.approx(0.9 * math.log(0.9) + 0.1 * math.log(0.1))
    # a class the fit never saw takes the pooled rate
    fitted, pooled = sf.rates(fit, ("d", "height"), prior=0.0)
    assert sf.log_likelihood({key(height=4, occupied=1): 1}, ("d", "height"), fitted,
                             pooled) == pytest.approx(math.log(0.5))
