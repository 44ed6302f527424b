#!/usr/bin/python3
"""Which features of an unobserved cell tell whether a scan that turns it known finds it occupied
(issue 51, item 1; RESULTS.md, "A prior learned from generated worlds"). The surface model
(docs/model.md) takes that chance from one feature, the cell's distance class to the nearest
occupied cell, fitted online per run; this measures what more features would tell, fitted on
generated piles and judged on other piles.

For each pile (`vantage scene generate --seed S`), from starts 0 and 1, the default planner's own
choices (ExploreEnv's reference) are followed for 14 scans on the hemisphere. Before each scan,
every unobserved cell's features are noted; after it, whether the scan turned it known, and
occupied. Features, all of them in every map:
  d      distance class to the nearest occupied cell: within 1, 2, 3, 4 cells, farther (4)
  free   free cells among its 6 face neighbours (0, 1, 2, 3 or more)
  unobs  unobserved cells among its 26 neighbours, in quarters (0-7, 8-15, 16-23, 24-26)
  height its layer above the grid's floor, the support of a table top: < 2, < 8, < 20, < 40, more
  below, above  an occupied cell within 4 cells straight below / above it (0 or 1)
Each feature set's rates are fitted per class on the fitting piles (a class no cell reached takes
the pooled rate; 20 cells of it as a prior) and judged on the held-out piles by the mean log
likelihood of the outcomes [nats per cell] of the cells within D (d < 4), the cells the model
credits: higher is better.

Usage: PYTHONPATH=build/release/python scripts/surface_features.py BUILD_VANTAGE \\
           [--fit 7001,7002,7003] [--judge 7004,7005,7006] [--scans 14]
BUILD_VANTAGE: the CLI that writes the piles (build/release/apps/vantage/vantage)."""
import argparse
import os
import subprocess
import sys
import tempfile
from collections import defaultdict

import numpy as np
import scipy.ndimage as ndi

import vantage

UNOBSERVED, FREE, OCCUPIED = 0, 1, 2
FEATURES = ("d", "free", "unobs", "height", "below", "above")
SETS = (("d",), ("d", "free"), ("d", "unobs"), ("d", "height"), ("d", "below", "above"),
        ("d", "free", "height"), ("d", "free", "unobs", "height", "below", "above"))
D = 4  # the model's cut-off [cells]


def column_within(occupied, up):
    """Per cell: an occupied cell within D cells straight above (up) or below it."""
    out = np.zeros(occupied.shape, bool)
    for k in range(1, D + 1):
        if up:
            out[:, :, :-k] |= occupied[:, :, k:]
        else:
            out[:, :, k:] |= occupied[:, :, :-k]
    return out


def features(cells):
    """Every cell's features (module docstring), each an int8 array of the grid's shape."""
    occupied, free = cells == OCCUPIED, cells == FREE
    dist = ndi.distance_transform_edt(~occupied) if occupied.any() else np.full(cells.shape, np.inf)
    d = np.where(dist <= 1, 0, np.where(dist <= D, np.ceil(dist) - 1, D))
    face = np.zeros(cells.shape, np.int8)
    for axis in range(3):
        padded = np.pad(free, [(1, 1) if a == axis else (0, 0) for a in range(3)])
        face += np.take(padded, range(0, cells.shape[axis]), axis=axis)
        face += np.take(padded, range(2, cells.shape[axis] + 2), axis=axis)
    unobs = ndi.uniform_filter((cells == UNOBSERVED).astype(np.float32), size=3,
                               mode="constant") * 27 - (cells == UNOBSERVED)
    z = np.broadcast_to(np.arange(cells.shape[2])[None, None, :], cells.shape)
    return {"d": d.astype(np.int8), "free": np.minimum(face, 3),
            "unobs": np.digitize(unobs, [7.5, 15.5, 23.5]).astype(np.int8),
            "height": np.digitize(z, [2, 8, 20, 40]).astype(np.int8),
            "below": column_within(occupied, False).astype(np.int8),
            "above": column_within(occupied, True).astype(np.int8)}


def outcomes(scene, scans):
    """(features..., occupied) -> cells turned known, over both starts' scans of `scene`."""
    counts = defaultdict(int)
    for start in (0, 1):
        env = vantage.ExploreEnv(scene, candidates="hemisphere", scans=scans, start=start,
                                 reference="latombe+surface", coverage_tolerance=0)
        obs, info = env.reset()
        while "reference" in info:
            before = obs["cells"].copy()
            f = features(before)
            obs, _, done, _, info = env.step(info["reference"]["view"])
            after = obs["cells"]
            known = (before == UNOBSERVED) & (after != UNOBSERVED)
            rows = np.stack([f[k][known] for k in FEATURES] + [after[known] == OCCUPIED], axis=1)
            keys, n = np.unique(rows.astype(np.int8), axis=0, return_counts=True)
            for key, count in zip(map(tuple, keys), n):
                counts[key] += int(count)
            if done:
                break
    return counts


def rates(counts, names, prior=20.0):
    """Per class of the features `names`: the fitted rate, and the pooled rate for the rest."""
    occ, known = defaultdict(float), defaultdict(float)
    index = [FEATURES.index(n) for n in names]
    for key, n in counts.items():
        if key[0] >= D:
            continue
        c = tuple(key[i] for i in index)
        known[c] += n
        occ[c] += n * key[-1]
    pooled = sum(occ.values()) / max(sum(known.values()), 1.0)
    return {c: (occ[c] + prior * pooled) / (known[c] + prior) for c in known}, pooled


def log_likelihood(counts, names, fitted, pooled):
    index = [FEATURES.index(n) for n in names]
    total = cells = 0.0
    for key, n in counts.items():
        if key[0] >= D:
            continue
        r = min(max(fitted.get(tuple(key[i] for i in index), pooled), 1e-4), 1 - 1e-4)
        total += n * (np.log(r) if key[-1] else np.log(1 - r))
        cells += n
    return total / cells


def merged(seeds, cli, scans, folder):
    counts = defaultdict(int)
    for seed in seeds:
        path = os.path.join(folder, f"pile-{seed}.yaml")
        subprocess.run([cli, "scene", "generate", "--seed", str(seed), "--out", path], check=True,
                       stdout=subprocess.DEVNULL)
        for key, n in outcomes(path, scans).items():
            counts[key] += n
        print(f"pile {seed}: done", file=sys.stderr, flush=True)
    return counts


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("cli")
    p.add_argument("--fit", default="7001,7002,7003")
    p.add_argument("--judge", default="7004,7005,7006")
    p.add_argument("--scans", type=int, default=14)
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        fit = merged([int(s) for s in a.fit.split(",")], a.cli, a.scans, folder)
        judge = merged([int(s) for s in a.judge.split(",")], a.cli, a.scans, folder)
    print(f"Fitted on piles {a.fit}, judged on piles {a.judge}; cells within D turned known.\n")
    print("| features | classes | held-out log likelihood [nats/cell] |\n|---|---|---|")
    for names in SETS:
        fitted, pooled = rates(fit, names)
        print(f"| {', '.join(names)} | {len(fitted)} | "
              f"{log_likelihood(judge, names, fitted, pooled):.4f} |")
    fitted, _ = rates(fit, ("d", "free"))
    print("\nRates by distance class (rows) and free face neighbours (columns), fitting piles:\n")
    print("| d | 0 | 1 | 2 | 3+ |\n|---|---|---|---|---|")
    for d in range(D):
        print(f"| {d} | " + " | ".join(f"{fitted.get((d, k), float('nan')):.3f}" for k in range(4))
              + " |")


if __name__ == "__main__":
    main()
