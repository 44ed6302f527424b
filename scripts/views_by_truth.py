#!/usr/bin/python3
"""Every method's choices judged by the truth alone (issue 36, docs/yardstick.md "Choices by the
truth"): the views each trial of a table-top sweep took, in order, scored by their noise-free hit
sets (DIR/yardstick/SCENE.json, the yardstick's own) rather than by the registered scans, so that
what a planner chose is measured apart from how registration went. The greedy oracle's order on
the same hit sets (set_cover.py's greedy_views) is the reference it is built to beat; beside it
the same oracle under the default planner's price of motion (truth-latombe: each view's new cells
times e^(-λ travel), λ the default's 0.5/m unless --lambda says): what a planner that knew the
world would reach, paying for motion as the default does.

Usage: views_by_truth.py DIR [--lambda L]
Reads DIR/scans.csv and DIR/yardstick/*.json; prints a Markdown table per method: trials, the
area above the true coverage curve over scans 1..N [scans] and its ratio to greedy's (pooled over
the same trials), the mean scans to 80, 90 and 95 % of V (N + 1 where not reached), the mean
travel over the N scans under the yardstick's travel rule [m], and the cases (trial, level) where
the greedy oracle's order on the truth needs more scans than the method's views; then each
method's mean true coverage after each scan.
"""

import argparse
import csv
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import set_cover  # noqa: E402  (the yardstick's hit sets and the greedy oracle's order)

LEVELS = (0.80, 0.90, 0.95)
DEFAULT_LAMBDA = 0.5  # PlannerConfig::lambda, the default planner's travel weight [1/m]


def curve(truth, start, views):
    """The true coverage (share of V) after the start's scan and after each view in turn."""
    hit = set(truth["starts"][start])
    out = [len(hit) / truth["visible_cells"]]
    for v in views:
        hit |= truth["views"][v]
        out.append(len(hit) / truth["visible_cells"])
    return out


def travel(truth, start, views):
    """The travel from the start through `views` in order, under the yardstick's rule [m]."""
    return sum(set_cover.travel_between(truth, start, here, v)
               for here, v in zip([None] + list(views[:-1]), views))


def scans_to(cov, level, budget):
    """The first scan (1-based) whose coverage reaches `level`; budget + 1 when none does."""
    for k, c in enumerate(cov[:budget]):
        if c >= level - 1e-12:
            return k + 1
    return budget + 1


def trials(out):
    """(scene, method, setting, trial) -> the views taken after the start, in scan order."""
    runs = defaultdict(list)
    with open(os.path.join(out, "scans.csv"), newline="") as f:
        for r in csv.DictReader(f):
            key = (r["scene"], r["method"], r.get("alpha", ""), r.get("objective", ""),
                   int(r["trial"]))
            runs[key].append((int(r["scan"]), int(r["view"])))
    return {k: [v for s, v in sorted(rows) if s > 1] for k, rows in runs.items()}


def measures(out, travel_weight=DEFAULT_LAMBDA):
    """Per trial: its method label, scene, trial, AAC, scans to each level and travel, by the
    truth; beside it the greedy oracle's order on the truth from the same start (label
    'truth-greedy') and that oracle priced by `travel_weight` [1/m] (label 'truth-latombe')."""
    truths = {}
    rows = []
    runs = trials(out)
    budget = max((len(v) + 1 for v in runs.values()), default=0)
    for (scene, method, alpha, objective, trial), views in sorted(runs.items()):
        if scene not in truths:
            path = os.path.join(out, "yardstick", f"{scene}.json")
            if not os.path.exists(path):
                continue
            truths[scene] = set_cover.load_truth(path)
        truth = truths[scene]
        start = trial % len(truth["starts"])
        name = method if not alpha else f"{method} (a={alpha}" + (
            f", {objective})" if objective else ")")
        oracle = [v for v, _ in set_cover.greedy_oracle(truth, start)]
        priced = [v for v, _ in set_cover.greedy_oracle(truth, start, travel_weight)]
        for label, order in ((name, views), ("truth-greedy", oracle), ("truth-latombe", priced)):
            cov = curve(truth, start, order)[:budget]
            cov += [cov[-1]] * (budget - len(cov))
            rows.append({"label": label, "scene": scene, "trial": trial, "curve": cov,
                         "aac": sum(1 - c for c in cov),
                         "travel": travel(truth, start, order[:budget - 1]),
                         **{lv: scans_to(cov, lv, budget) for lv in LEVELS}})
    return rows, budget


ORACLES = ("truth-greedy", "truth-latombe")


def per_label(rows, label):
    """The rows of `label`; an oracle's once per scene and start, whatever the methods."""
    mine = [r for r in rows if r["label"] == label]
    return list({(r["scene"], r["trial"]): r for r in mine}.values()) if label in ORACLES else mine


def table(rows, budget):
    oracle = {(r["scene"], r["trial"]): r for r in rows if r["label"] == "truth-greedy"}
    greedy = {(r["scene"], r["trial"]): r for r in rows if r["label"] == "greedy"}
    lines = ["| method | trials | AAC by the truth [scans] | × greedy's | " +
             " | ".join(f"scans to {round(100 * lv)}%" for lv in LEVELS) +
             " | travel [m] | the oracle's order behind it (cases) |",
             "|---|---|---|---|" + "---|" * len(LEVELS) + "---|---|"]
    labels = sorted({r["label"] for r in rows if r["label"] not in ORACLES})
    for label in list(ORACLES) + labels:
        mine = per_label(rows, label)
        n = len(mine)
        pairs = [(r["aac"], greedy[(r["scene"], r["trial"])]["aac"]) for r in mine
                 if (r["scene"], r["trial"]) in greedy]
        ratio = (sum(a for a, _ in pairs) / sum(g for _, g in pairs)
                 if pairs and len(pairs) == n and sum(g for _, g in pairs) > 0 else None)
        behind = sum(oracle[(r["scene"], r["trial"])][lv] > r[lv] for r in mine for lv in LEVELS)
        lines.append(f"| {label} | {n} | {sum(r['aac'] for r in mine) / n:.3f} | "
                     f"{'-' if ratio is None else f'{ratio:.3f}'} | " +
                     " | ".join(f"{sum(r[lv] for r in mine) / n:.2f}" for lv in LEVELS) +
                     f" | {sum(r['travel'] for r in mine) / n:.2f}"
                     f" | {behind} of {n * len(LEVELS)} |")
    return lines


def curves(rows, budget):
    """Per method, the mean true coverage (share of V) after each scan: where a method falls
    behind the oracle, scan by scan."""
    lines = ["| method | " + " | ".join(f"scan {k}" for k in range(1, budget + 1)) + " |",
             "|---|" + "---|" * budget]
    labels = sorted({r["label"] for r in rows if r["label"] not in ORACLES})
    for label in list(ORACLES) + labels:
        mine = per_label(rows, label)
        lines.append(f"| {label} | " + " | ".join(
            f"{sum(r['curve'][k] for r in mine) / len(mine):.3f}" for k in range(budget)) + " |")
    return lines


def lambda_arg(text):
    """--lambda: a travel weight >= 0 [1/m]."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (value >= 0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"must be a number >= 0 [1/m], got '{text}'")
    return value


def main(argv):
    parser = argparse.ArgumentParser(prog="views_by_truth.py",
                                     description="A sweep's choices judged by the truth.")
    parser.add_argument("dir", help="the sweep's folder (scans.csv, yardstick/)")
    parser.add_argument("--lambda", dest="travel_weight", type=lambda_arg, default=DEFAULT_LAMBDA,
                        help="truth-latombe's travel weight [1/m] (default: the default "
                             f"planner's, {DEFAULT_LAMBDA})")
    args = parser.parse_args(argv[1:])
    out = args.dir
    if not os.path.exists(os.path.join(out, "scans.csv")):
        sys.exit(f"views_by_truth.py: no {out}/scans.csv")
    rows, budget = measures(out, args.travel_weight)
    if not rows:
        sys.exit(f"views_by_truth.py: no trial of {out}/scans.csv has a yardstick file")
    print(f"Scans 1..{budget} (the start's included); truth-greedy = the greedy oracle's order on"
          " the noise-free hit sets from the same start; truth-latombe = the same priced by"
          f" e^(-{args.travel_weight:g} travel).\n")
    print("\n".join(table(rows, budget)))
    print("\nThe mean true coverage after each scan:\n")
    print("\n".join(curves(rows, budget)))


if __name__ == "__main__":
    main(sys.argv)
