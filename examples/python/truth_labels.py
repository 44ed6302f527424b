#!/usr/bin/env python3
"""Training labels for a learned planner from ExploreEnv's truth: at each state of an episode,
every candidate's new true surface cells, the cells of the visible object surface its noise-free
scan would cover that the start's and the taken views' scans have not (what SCVP and PC-NBV
learn to predict). The observation never holds the truth; the labels are for training and for
judging, and a policy benched with `vt.bench_policy` sees only the observation.

Taking the candidate of the largest label (ties to the shorter travel, then the lower index) is
the greedy oracle, `vantage bench --methods greedy-oracle` (python/tests/test_env.py holds it to
the bench's trial, view for view).

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/truth_labels.py [OUT.npz]

runs two episodes of tabletop-1's ring, the first scans following the built-in default's
choices, and writes each state's occupancy classes, candidate poses, taken mask, travel and
labels to OUT.npz (default: labels.npz in a fresh temporary folder).
"""

import pathlib
import sys
import tempfile

import numpy as np

import vantage as vt


class Labeller:
    """Every candidate's new true cells along one episode; `taken(view)` after each step."""

    def __init__(self, env, start):
        truth = env.truth
        self.views = truth["views"]
        self.hit = np.zeros(env.grid.num_cells, bool)
        self.hit[truth["starts"][start]] = True

    def labels(self, obs):
        """Per candidate, its new true cells [cells]; -1 where taken."""
        out = np.array([np.count_nonzero(~self.hit[v]) for v in self.views])
        out[obs["taken"]] = -1
        return out

    def taken(self, view):
        self.hit[self.views[view]] = True


def oracle_choice(labels, travel):
    """The greedy oracle's view: the largest label, then the shorter travel, then the lower
    index."""
    return int(min(np.flatnonzero(labels >= 0), key=lambda c: (-labels[c], travel[c], c)))


def episode(env, start, seed, policy):
    """(cells, taken, travel, labels) at each decision of one episode under `policy(obs, info,
    labels)`."""
    labeller = Labeller(env, start)
    obs, info = env.reset(seed=seed)
    states, done = [], False
    while not done:
        labels = labeller.labels(obs)
        states.append((obs["cells"], obs["taken"].copy(), obs["travel"].copy(), labels))
        view = policy(obs, info, labels)
        labeller.taken(view)
        obs, _, done, _, info = env.step(view)
    return states


def main(argv):
    out = (pathlib.Path(argv[1]) if len(argv) > 1
           else pathlib.Path(tempfile.mkdtemp()) / "labels.npz")
    rows = []
    for start in (0, 1):
        env = vt.ExploreEnv("tabletop-1", scans=6, seed=1, start=start, reference="latombe+surface")
        rows += episode(env, start, 1, lambda obs, info, labels: info["reference"]["view"])
    cells, taken, travel, labels = (np.stack(column) for column in zip(*rows))
    np.savez_compressed(out, cells=cells, taken=taken, travel=travel, labels=labels,
                        candidates=env.candidates)
    print(f"{len(rows)} states, {labels.shape[1]} candidates each: {out}")


if __name__ == "__main__":
    main(sys.argv)
