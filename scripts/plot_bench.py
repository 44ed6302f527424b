#!/usr/bin/python3
"""Plots and summarises a sweep (`vantage bench`): the paper's Figs. 10 and 11.

Usage: plot_bench.py DIR
Reads DIR/scans.csv; writes DIR/unobserved.png (mean +- std of unobserved cells per scan, per
method and scene), DIR/prediction_error.png (absolute error of predicted vs actual gain per scan,
probabilistic vs greedy predictions on the probabilistic run's poses) and DIR/summary.md.
"""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"probabilistic": "#d32f2f", "greedy": "#1976d2", "random": "#388e3c",
           "latombe": "#7b1fa2", "yamauchi": "#f57c00"}


def mean_std(values):
    n = len(values)
    if n == 0:
        return float("nan"), float("nan")
    m = sum(values) / n
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / n)


def label(method, alpha):
    return f"{method} (a={alpha})" if method == "probabilistic" else method


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_bench.py: {path} has no rows")
    return rows


def grouped(rows):
    """(scene, method, alpha) -> scan -> list of rows (one per trial)."""
    g = defaultdict(lambda: defaultdict(list))
    for r in rows:
        g[(r["scene"], r["method"], r["alpha"])][int(r["scan"])].append(r)
    return g


def grid_axes(n):
    cols = min(n, 2)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6.0 * cols, 4.0 * rows), squeeze=False)
    return fig, [ax for row in axes for ax in row]


def plot_unobserved(out, scenes, g):
    fig, axes = grid_axes(len(scenes))
    for ax, scene in zip(axes, scenes):
        for (s, method, alpha), by_scan in sorted(g.items()):
            if s != scene:
                continue
            scans = sorted(by_scan)
            stats = [mean_std([float(r["unobserved"]) for r in by_scan[k]]) for k in scans]
            m = [x[0] for x in stats]
            sd = [x[1] for x in stats]
            colour = COLOURS.get(method)
            ax.plot(scans, m, "o-", ms=3, color=colour, label=label(method, alpha))
            ax.fill_between(scans, [a - b for a, b in zip(m, sd)], [a + b for a, b in zip(m, sd)],
                            color=colour, alpha=0.15)
        ax.set_title(scene)
        ax.set_xlabel("scan")
        ax.set_ylabel("unobserved cells")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    for ax in axes[len(scenes):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "unobserved.png"), dpi=110)
    plt.close(fig)


def prediction_errors(by_scan):
    """scan -> (errors of the method's prediction, errors of greedy's on the same poses)."""
    result = {}
    for k, rows in sorted(by_scan.items()):
        own = [abs(float(r["predicted_gain"]) - float(r["actual_gain"]))
               for r in rows if r["predicted_gain"]]
        greedy = [abs(float(r["greedy_predicted_gain"]) - float(r["actual_gain"]))
                  for r in rows if r["greedy_predicted_gain"]]
        if own:
            result[k] = (own, greedy)
    return result


def plot_prediction_error(out, scenes, g):
    fig, axes = grid_axes(len(scenes))
    for ax, scene in zip(axes, scenes):
        for (s, method, alpha), by_scan in sorted(g.items()):
            if s != scene or method != "probabilistic":
                continue
            errs = prediction_errors(by_scan)
            scans = sorted(errs)
            own = [mean_std(errs[k][0]) for k in scans]
            greedy = [mean_std(errs[k][1]) for k in scans]
            ax.errorbar(scans, [x[0] for x in own], yerr=[x[1] for x in own], fmt="o-", ms=3,
                        capsize=2, color=COLOURS["probabilistic"],
                        label=f"probabilistic prediction (a={alpha})")
            ax.errorbar(scans, [x[0] for x in greedy], yerr=[x[1] for x in greedy], fmt="s--",
                        ms=3, capsize=2, color=COLOURS["greedy"],
                        label=f"greedy prediction, same poses (a={alpha} run)")
        ax.set_title(scene)
        ax.set_xlabel("scan")
        ax.set_ylabel("|predicted - actual| gain [cells]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    for ax in axes[len(scenes):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "prediction_error.png"), dpi=110)
    plt.close(fig)


def summary(out, scenes, g):
    lines = ["# Sweep summary", "",
             "Mean unobserved cells after scans 2, 4, 6 and 8 (over trials); AUC = area under the",
             "mean unobserved-cells curve (trapezoid, per scan); prediction error = mean",
             "|predicted - actual| gain over scans 2.. of the method's own prediction (greedy's",
             "prediction on the same poses in brackets); plan time = mean seconds per decision.",
             ""]
    for scene in scenes:
        lines += [f"## {scene}", "",
                  "| method | trials | @2 | @4 | @6 | @8 | AUC | prediction error | plan [s] |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for (s, method, alpha), by_scan in sorted(g.items()):
            if s != scene:
                continue
            scans = sorted(by_scan)
            means = {k: mean_std([float(r["unobserved"]) for r in by_scan[k]])[0] for k in scans}
            cells = [f"{means[k]:.0f}" if k in means else "-" for k in (2, 4, 6, 8)]
            auc = sum((means[a] + means[b]) / 2 for a, b in zip(scans, scans[1:]))
            errs = prediction_errors(by_scan)
            own = [e for k in errs for e in errs[k][0]]
            greedy = [e for k in errs for e in errs[k][1]]
            err = f"{mean_std(own)[0]:.0f} ({mean_std(greedy)[0]:.0f})" if own else "-"
            plan = [float(r["plan_seconds"]) for k in scans if k > 1 for r in by_scan[k]]
            trials = len(by_scan[scans[0]])
            lines.append(f"| {label(method, alpha)} | {trials} | " + " | ".join(cells) +
                         f" | {auc:.0f} | {err} | {mean_std(plan)[0]:.3f} |")
        lines.append("")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines))


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: plot_bench.py DIR")
    out = argv[1]
    rows = load(os.path.join(out, "scans.csv"))
    scenes = sorted({r["scene"] for r in rows})
    g = grouped(rows)
    plot_unobserved(out, scenes, g)
    plot_prediction_error(out, scenes, g)
    summary(out, scenes, g)


if __name__ == "__main__":
    main(sys.argv)
