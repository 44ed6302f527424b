#!/usr/bin/python3
"""Where a planner's gap to the greedy oracle lies by the truth, cell by cell (issue 51;
RESULTS.md, "Where the gap by the truth lies"): the planner's own choices are followed
(ExploreEnv's reference) on generated piles, and at each decision the cells that the view it
chose and the best view by the truth (the most new true cells; ties to the shorter travel, then
the lower index, as the greedy oracle breaks them) would newly hit are sorted by what the map
holds of them before the scan:
  occupied   by its log-odds: one net hit (below 0.85, logit(0.7) the hit's step), two, three or
             more
  free
  unobserved within one cell of an occupied cell (Chebyshev), or farther
The best view's rank in the planner's order (its predicted gain times e^(-λ travel) for a method
ranked by travel, λ the default's 0.5 /m; the gain alone otherwise) says how far the planner was
from choosing it. Decisions are grouped by the scan they choose: 2-4, 5-7, 8 and later.

Usage: PYTHONPATH=build/release/python scripts/gap_by_cell_state.py BUILD_VANTAGE \\
           [--seeds 1001,1002,1003,1004] [--starts 2] [--scans 14] [--method latombe+surface]
BUILD_VANTAGE: the CLI that writes the piles (build/release/apps/vantage/vantage). The hemisphere
`explore` builds, no tolerance, the sweep seed 1: trial t of `vantage bench tabletop --generated
N --generated-seed S --trials T` from start t."""
import argparse
import math
import os
import subprocess
import sys
import tempfile
from collections import Counter, defaultdict

import numpy as np
import scipy.ndimage as ndi

import vantage

UNOBSERVED, FREE, OCCUPIED = 0, 1, 2
HIT = math.log(0.7 / 0.3)  # OccupancyParams::p_hit's step of the log-odds
LAMBDA = 0.5  # PlannerConfig::lambda [1/m]
KINDS = ("occupied, 1 hit", "occupied, 2 hits", "occupied, 3+ hits", "free", "unobserved, <= 1",
         "unobserved, farther")
PHASES = ((2, 4), (5, 7), (8, None))


def new_cells(views, hit, candidates):
    """Per candidate, the cells of its true hit set that `hit` (a bool per grid cell) lacks."""
    return {c: views[c][~hit[views[c]]] for c in candidates}


def best_view(fresh, travel):
    """The greedy oracle's view: most new cells, then the shorter travel, then the lower index."""
    return min(fresh, key=lambda c: (-len(fresh[c]), travel[c], c))


def distance_to_occupied(cells):
    """Per cell (flat, x fastest), its Chebyshev distance to the nearest occupied cell [cells];
    a large number when the map has none."""
    occupied = cells == OCCUPIED
    if not occupied.any():
        return np.full(cells.size, np.iinfo(np.int32).max)
    d = ndi.distance_transform_cdt(~occupied, metric="chessboard")
    return d.ravel(order="F")


def kinds(cells_new, cells, log_odds, distance):
    """How many of the flat indices `cells_new` the map holds as each of KINDS."""
    state = cells.ravel(order="F")[cells_new]
    l = log_odds.ravel(order="F")[cells_new]
    d = distance[cells_new]
    hits = np.floor(l / (HIT + 1e-3)).astype(np.int64)  # 0 below one hit's step and a bit
    occupied = state == OCCUPIED
    unobserved = state == UNOBSERVED
    return Counter({
        KINDS[0]: int((occupied & (hits <= 0)).sum()),
        KINDS[1]: int((occupied & (hits == 1)).sum()),
        KINDS[2]: int((occupied & (hits >= 2)).sum()),
        KINDS[3]: int((state == FREE).sum()),
        KINDS[4]: int((unobserved & (d <= 1)).sum()),
        KINDS[5]: int((unobserved & (d > 1)).sum())})


def rank(gains, travel, best, candidates, by_travel):
    """How many open candidates the planner scored above `best`."""
    score = gains * (np.exp(-LAMBDA * travel) if by_travel else 1.0)
    return int(sum(score[c] > score[best] for c in candidates))


def phase(scan):
    return next(k for k, (lo, hi) in enumerate(PHASES) if scan >= lo and (hi is None or scan <= hi))


def phase_totals():
    """Per phase: the chosen and the best views' kinds and new cells, decisions and ranks."""
    return defaultdict(lambda: {"chosen": Counter(), "best": Counter(), "n": 0, "ranks": [],
                                "new": Counter()})


def decisions(scene, starts, scans, method):
    """phase_totals() over the decisions of `method`'s runs of `scene`."""
    out = phase_totals()
    by_travel = method.startswith("latombe")
    for start in range(starts):
        env = vantage.ExploreEnv(scene, candidates="hemisphere", scans=scans, start=start,
                                 reference=method, coverage_tolerance=0)
        truth = env.truth
        views = truth["views"]
        obs, info = env.reset()
        hit = np.zeros(obs["cells"].size, bool)
        hit[truth["starts"][start]] = True
        while "reference" in info:
            candidates = np.flatnonzero(~obs["taken"])
            fresh = new_cells(views, hit, candidates)
            best = best_view(fresh, obs["travel"])
            chosen = info["reference"]["view"]
            distance = distance_to_occupied(obs["cells"])
            p = out[phase(obs["scan"] + 1)]
            p["n"] += 1
            p["chosen"] += kinds(fresh[chosen], obs["cells"], obs["log_odds"], distance)
            p["best"] += kinds(fresh[best], obs["cells"], obs["log_odds"], distance)
            p["new"]["chosen"] += len(fresh[chosen])
            p["new"]["best"] += len(fresh[best])
            p["ranks"].append(rank(info["reference"]["gains"], obs["travel"], best, candidates,
                                   by_travel))
            hit[views[chosen]] = True
            obs, _, done, _, info = env.step(chosen)
            if done:
                break
    return out


def table(phases):
    lines = ["| decisions for scans | runs' decisions | new true cells: chosen / best | of the "
             "best's: " + " / ".join(KINDS) + " [%] | the best's rank (median) |",
             "|---|---|---|---|---|"]
    for k, (lo, hi) in enumerate(PHASES):
        p = phases.get(k)
        if not p or not p["n"]:
            continue
        total = sum(p["best"].values()) or 1
        lines.append(f"| {lo}-{hi if hi else ''} | {p['n']} | {p['new']['chosen'] / p['n']:.0f} / "
                     f"{p['new']['best'] / p['n']:.0f} | "
                     + " / ".join(f"{100 * p['best'][kind] / total:.0f}" for kind in KINDS)
                     + f" | {float(np.median(p['ranks'])):g} |")
    return lines


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("cli")
    p.add_argument("--seeds", default="1001,1002,1003,1004")
    p.add_argument("--starts", type=int, default=2)
    p.add_argument("--scans", type=int, default=14)
    p.add_argument("--method", default="latombe+surface")
    a = p.parse_args()
    phases = phase_totals()
    with tempfile.TemporaryDirectory() as folder:
        for seed in (int(s) for s in a.seeds.split(",")):
            path = os.path.join(folder, f"pile-{seed}.yaml")
            subprocess.run([a.cli, "scene", "generate", "--seed", str(seed), "--out", path],
                           check=True, stdout=subprocess.DEVNULL)
            for k, d in decisions(path, a.starts, a.scans, a.method).items():
                q = phases[k]
                for key in ("chosen", "best", "new"):
                    q[key] += d[key]
                q["n"] += d["n"]
                q["ranks"] += d["ranks"]
            print(f"pile {seed}: done", file=sys.stderr, flush=True)
    print(f"{a.method} on piles {a.seeds}, starts 0-{a.starts - 1}, {a.scans} scans, the "
          "hemisphere, no tolerance.\n")
    print("\n".join(table(phases)))


if __name__ == "__main__":
    main()
