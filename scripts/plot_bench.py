#!/usr/bin/python3
"""Plots and summarises a sweep (`vantage bench`): the paper's Figs. 10 and 11 (table top) and
Figs. 15 and 16 (office).

Usage: plot_bench.py DIR [--levels 90,95]
Reads DIR/scans.csv; writes DIR/unobserved.png (mean +- std of unobserved cells per scan, per
method and scene), DIR/unobserved_by_travel.png (the same against the distance travelled),
DIR/prediction_error.png (absolute error of the predicted vs the actual number of cells seen
per scan: the probabilistic method's expected cells seen (predicted_cells) against greedy's count
on the same poses, the paper's Fig. 11), DIR/trials.csv (one row per trial: AUC, travel, and the
scans and travel to reach 90 % and 95 % of the observable surface, or the --levels given, in
percent) and DIR/summary.md, which ends
with each method's paired differences from greedy over scenes and starts, with a Wilcoxon
signed-rank test (scipy).

The probabilistic method's curves are told apart by its a setting (a number or 'auto') and its
objective (what it ranks by: bits or cells).

A trial that stopped early (no frontier left) keeps its last map: its last figures stand for the
later scans, so that every mean is over all trials.

When scans.csv holds surface_coverage (table tops, docs/yardstick.md: a visible object-surface
cell covered once a registered scan point lies within one cell of it), summary.md also holds the
scans and travel to 80, 90 and 95 % of it per method (censored where not reached), the area above
each coverage curve and each method's share of the gap between greedy and the greedy oracle
(greedy-oracle) it closes, with a paired Wilcoxon test; DIR/coverage_travel.png plots the area
under the surface-coverage curve against travel, a point per method, with the Pareto front; and
DIR/set_cover.csv (scripts/set_cover.py), when present, adds the set-cover bound per scene, start
and level.
"""
import csv
import json
import math
import os
import sys
import warnings
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"probabilistic": "#d32f2f", "survival": "#ad1457", "greedy": "#1976d2",
           "random": "#388e3c",
           "latombe": "#7b1fa2", "yamauchi": "#f57c00",
           # The field's metrics (docs/model.md "The field's metrics").
           "occlusion-aware": "#00838f", "unobserved-voxel": "#6d4c41",
           "rear-side-voxel": "#c2185b", "rear-side-entropy": "#9e9d24",
           "proximity-count": "#5e35b1", "average-entropy": "#546e7a", "area-factor": "#ef6c00",
           "greedy-oracle": "#000000"}
# Methods whose prediction in cells is their own (the paper's model's expected cells seen, each
# metric's unobserved-voxel count on its poses), plotted against the actual cells seen.
PREDICTING = {"probabilistic", "survival", "occlusion-aware", "unobserved-voxel", "rear-side-voxel",
              "rear-side-entropy", "proximity-count", "average-entropy", "area-factor"}


def mean_std(values):
    n = len(values)
    if n == 0:
        return float("nan"), float("nan")
    m = sum(values) / n
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / n)


# Further a values of the probabilistic method, each in its own shade of its colour.
PROBABILISTIC_SHADES = ["#d32f2f", "#ff8a80", "#8e0000", "#f06292", "#5d4037"]


def setting_order(setting):
    """Sorts the probabilistic settings: numeric a ascending, then 'auto'; bits before cells."""
    alpha, objective = setting
    try:
        return (0, float(alpha), objective)
    except ValueError:
        return (1, 0.0, objective)


def colour(g, method, setting):
    """The colour of one curve: the method's, and for the probabilistic method one shade per
    setting (a and objective) in the sweep, so that an a study's curves can be told apart."""
    if method != "probabilistic":
        return COLOURS.get(method)
    settings = sorted({k[2] for k in g if k[1] == "probabilistic"}, key=setting_order)
    return PROBABILISTIC_SHADES[settings.index(setting) % len(PROBABILISTIC_SHADES)]


def label(method, setting):
    if method not in ("probabilistic", "survival"):
        return method
    alpha, objective = setting
    return f"{method} (a={alpha}, {objective})" if objective else f"{method} (a={alpha})"


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_bench.py: {path} has no rows")
    return rows


def grouped(rows):
    """(scene, method, alpha) -> scan -> list of rows (one per trial), trials that stopped early
    carried forward to the group's last scan."""
    trials = defaultdict(lambda: defaultdict(list))
    for r in rows:
        setting = (r["alpha"], r.get("objective") or "")
        trials[(r["scene"], r["method"], setting)][r["trial"]].append(r)
    g = defaultdict(lambda: defaultdict(list))
    for key, by_trial in trials.items():
        last = max(int(r["scan"]) for rs in by_trial.values() for r in rs)
        for rs in by_trial.values():
            rs.sort(key=lambda r: int(r["scan"]))
            for r in rs:
                g[key][int(r["scan"])].append(r)
            for k in range(int(rs[-1]["scan"]) + 1, last + 1):
                g[key][k].append(dict(rs[-1], scan=str(k), predicted_gain="",
                                      predicted_cells="", greedy_predicted_gain="",
                                      actual_gain="0", travel_m="0", fallback="0", carried="1"))
    return g


def travelled(by_scan):
    """trial -> list of (cumulative travel [m], unobserved cells) by scan."""
    curves = defaultdict(list)
    for k in sorted(by_scan):
        for r in by_scan[k]:
            c = curves[r["trial"]]
            total = (c[-1][0] if c else 0.0) + float(r.get("travel_m") or 0.0)
            c.append((total, float(r["unobserved"])))
    return curves


def at_distance(curve, d):
    """Unobserved cells of a trial once it has travelled d: its last scan taken within d."""
    value = curve[0][1]
    for total, unobserved in curve:
        if total > d + 1e-9:
            break
        value = unobserved
    return value


def grid_axes(n):
    cols = min(n, 2)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6.0 * cols, 4.0 * rows), squeeze=False)
    return fig, [ax for row in axes for ax in row]


def legend_if_any(ax):
    """A legend for the panel's labelled lines; a panel with none (no run of a method it draws
    in that scene) says so instead of an empty legend."""
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    else:
        ax.text(0.5, 0.5, "no run to draw", transform=ax.transAxes, ha="center", va="center",
                color="0.5")


def plot_curves(out, name, xlabel, scenes, g, curve):
    """One panel per scene with the mean +- std of unobserved cells of every (method, a):
    `curve(by_scan)` gives (xs, per-x lists over trials, line style, band opacity), or None."""
    fig, axes = grid_axes(len(scenes))
    for ax, scene in zip(axes, scenes):
        for (s, method, alpha), by_scan in sorted(g.items()):
            if s != scene:
                continue
            drawn = curve(by_scan)
            if drawn is None:
                continue
            xs, samples, style, opacity = drawn
            stats = [mean_std(v) for v in samples]
            m = [x[0] for x in stats]
            sd = [x[1] for x in stats]
            c = colour(g, method, alpha)
            ax.plot(xs, m, style, ms=3, color=c, label=label(method, alpha))
            ax.fill_between(xs, [a - b for a, b in zip(m, sd)], [a + b for a, b in zip(m, sd)],
                            color=c, alpha=opacity)
        ax.set_title(scene)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("unobserved cells")
        ax.grid(alpha=0.3)
        legend_if_any(ax)
    for ax in axes[len(scenes):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=110)
    plt.close(fig)


def plot_unobserved(out, scenes, g):
    def by_scan_curve(by_scan):
        scans = sorted(by_scan)
        return scans, [[float(r["unobserved"]) for r in by_scan[k]] for k in scans], "o-", 0.15

    plot_curves(out, "unobserved.png", "scan", scenes, g, by_scan_curve)


def plot_unobserved_by_travel(out, scenes, g):
    def by_travel_curve(by_scan):
        curves = travelled(by_scan)
        longest = max(c[-1][0] for c in curves.values())
        if longest <= 0:
            return None
        xs = [longest * i / 200 for i in range(201)]
        return xs, [[at_distance(c, d) for c in curves.values()] for d in xs], "-", 0.12

    plot_curves(out, "unobserved_by_travel.png", "distance travelled [m]", scenes, g,
                by_travel_curve)


def predicted_cells(r):
    """The method's prediction of the cells a scan sees [cells], or '' for the first scan. Sweeps
    from before predicted_cells existed predicted only in bits: those carry no cell prediction."""
    return r.get("predicted_cells") or ""


def prediction_errors(by_scan):
    """scan -> (errors of the method's prediction, errors of greedy's on the same poses), both
    in cells seen, as the paper's §5.2 defines the error."""
    result = {}
    for k, rows in sorted(by_scan.items()):
        rows = [r for r in rows if "carried" not in r]
        own = [abs(float(predicted_cells(r)) - float(r["actual_gain"]))
               for r in rows if predicted_cells(r)]
        greedy = [abs(float(r["greedy_predicted_gain"]) - float(r["actual_gain"]))
                  for r in rows if r["greedy_predicted_gain"]]
        if own:
            result[k] = (own, greedy)
    return result


def plot_prediction_error(out, scenes, g):
    fig, axes = grid_axes(len(scenes))
    for ax, scene in zip(axes, scenes):
        for (s, method, alpha), by_scan in sorted(g.items()):
            if s != scene or method not in PREDICTING:
                continue
            errs = prediction_errors(by_scan)
            scans = sorted(errs)
            own = [mean_std(errs[k][0]) for k in scans]
            greedy = [mean_std(errs[k][1]) for k in scans]
            ax.errorbar(scans, [x[0] for x in own], yerr=[x[1] for x in own], fmt="o-", ms=3,
                        capsize=2, color=colour(g, method, alpha),
                        label=f"{label(method, alpha)}: expected cells seen")
            if method not in ("probabilistic", "survival"):
                continue  # greedy's reference once per panel is enough to read it by
            ax.errorbar(scans, [x[0] for x in greedy], yerr=[x[1] for x in greedy], fmt="s--",
                        ms=3, capsize=2, color=COLOURS["greedy"], alpha=0.6,
                        label=f"greedy's count on the same poses ({label(method, alpha)} run)")
        ax.set_title(scene)
        ax.set_xlabel("scan")
        ax.set_ylabel("|predicted - actual| cells seen [cells]")
        ax.grid(alpha=0.3)
        legend_if_any(ax)
    for ax in axes[len(scenes):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "prediction_error.png"), dpi=110)
    plt.close(fig)


def checkpoints(last):
    """Scans to report: 2, 4, 6, 8 for short runs, quarters of the run for long ones."""
    if last <= 10:
        return [2, 4, 6, 8]
    return sorted({max(2, round(last * q / 4)) for q in (1, 2, 3, 4)})


def reduction_curve(by_scan):
    """scan -> mean over trials of the cells that left the unobserved set since the first scan."""
    first = {r["trial"]: float(r["unobserved"]) for r in by_scan[min(by_scan)]}
    return {k: mean_std([first[r["trial"]] - float(r["unobserved"]) for r in rows])[0]
            for k, rows in sorted(by_scan.items())}


def scans_to(curve, target):
    """The (fractional, linearly interpolated) scan at which a mean reduction curve first reaches
    `target`, or None."""
    scans = sorted(curve)
    for a, b in zip(scans, scans[1:]):
        if curve[b] >= target > curve[a]:
            return a + (b - a) * (target - curve[a]) / (curve[b] - curve[a])
    return None


def summary(out, scenes, g, paired=()):
    last = max(k for by_scan in g.values() for k in by_scan)
    marks = checkpoints(last)
    lines = ["# Sweep summary", "",
             f"Mean unobserved cells after scans {', '.join(map(str, marks))} (over trials); AUC =",
             "area under the mean unobserved-cells curve (trapezoid, per scan) [cells x scans], and",
             "as a share of greedy's; coverage = mean observed share of the observable surface",
             "after the last scan; prediction error = mean |predicted - actual| cells seen over",
             "scans 2.. of the method's own prediction in cells (greedy's count on the same poses",
             "in brackets); plan time = mean seconds per decision; travel = mean distance",
             "travelled per trial [m]; fallbacks = mean stops per trial whose goal was not",
             "reachable; scans to X% = the scan at which the method's mean reduction of",
             "unobserved cells since scan 1 reaches X% of the largest mean reduction any method of",
             "the scene reached by the last scan (interpolated; '-' = not reached).",
             ""]
    for scene in scenes:
        curves = {key: reduction_curve(by_scan) for key, by_scan in g.items() if key[0] == scene}
        best = max(c[max(c)] for c in curves.values())
        aucs = {}
        for key, by_scan in g.items():
            if key[0] != scene:
                continue
            scans = sorted(by_scan)
            means = [mean_std([float(r["unobserved"]) for r in by_scan[k]])[0] for k in scans]
            aucs[key] = sum((a + b) / 2 for a, b in zip(means, means[1:]))
        greedy_auc = [v for k, v in aucs.items() if k[1] == "greedy"]
        lines += [f"## {scene}", "",
                  "| method | trials | " + " | ".join(f"@{k}" for k in marks) +
                  " | AUC | AUC / greedy | coverage | prediction error [cells] | plan [s] |"
                  " travel [m] | fallbacks | scans to 50% | scans to 75% |",
                  "|---|---|" + "---|" * len(marks) + "---|---|---|---|---|---|---|---|---|"]
        for key, by_scan in sorted(g.items(), key=lambda kv: (kv[0][1], setting_order(kv[0][2]))):
            s, method, setting = key
            if s != scene:
                continue
            scans = sorted(by_scan)
            means = {k: mean_std([float(r["unobserved"]) for r in by_scan[k]])[0] for k in scans}
            cells = [f"{means[k]:.0f}" if k in means else "-" for k in marks]
            # NOTE: a run of one scan has no area under its curve (0): no ratio to greedy.
            ratio = f"{aucs[key] / greedy_auc[0]:.3f}" if greedy_auc and greedy_auc[0] else "-"
            coverage = mean_std([float(r["coverage"]) for r in by_scan[scans[-1]]])[0]
            errs = prediction_errors(by_scan)
            own = [e for k in errs for e in errs[k][0]]
            greedy = [e for k in errs for e in errs[k][1]]
            err = f"{mean_std(own)[0]:.0f} ({mean_std(greedy)[0]:.0f})" if own else "-"
            real = [r for k in scans for r in by_scan[k] if "carried" not in r]
            plan = [float(r["plan_seconds"]) for r in real if int(r["scan"]) > 1]
            trials = len(by_scan[scans[0]])
            travel = sum(float(r.get("travel_m") or 0.0) for r in real) / trials
            fallbacks = sum(int(r.get("fallback") or 0) for r in real) / trials
            reach = [scans_to(curves[key], share * best) for share in (0.5, 0.75)]
            reach = [f"{x:.1f}" if x is not None else "-" for x in reach]
            lines.append(f"| {label(method, setting)} | {trials} | " + " | ".join(cells) +
                         f" | {aucs[key]:.0f} | {ratio} | {100 * coverage:.1f}% | {err} |"
                         f" {mean_std(plan)[0]:.3f} | {travel:.1f} | {fallbacks:.1f} |"
                         f" {reach[0]} | {reach[1]} |")
        lines.append("")
    lines += paired
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines))


# Coverage levels whose scans and travel each trial records (shares of the observable surface).
LEVELS = (0.90, 0.95)


def trial_rows(g):
    """Each trial's rows in scan order: ((scene, method, setting), trial, rows) for every group of
    grouped()."""
    for key, by_scan in g.items():
        by_trial = defaultdict(list)
        for k in sorted(by_scan):
            for r in by_scan[k]:
                by_trial[r["trial"]].append(r)
        for trial, rows in by_trial.items():
            yield key, trial, rows


def trial_metrics(g):
    """One dict per trial (scene, method, setting, trial): its AUC [cells x scans] (trapezoid over
    scans 1..last, a trial that stopped early carried forward), travel [m], final coverage, and
    for each level the first scan whose coverage reaches it and the travel up to and including
    that scan, None when no scan of the trial reaches it (censored)."""
    trials = []
    for (scene, method, setting), trial, rows in trial_rows(g):
        unobserved = [float(r["unobserved"]) for r in rows]
        m = {"scene": scene, "method": method, "setting": setting, "trial": trial,
             "scans": len(rows),
             "auc": sum((a + b) / 2 for a, b in zip(unobserved, unobserved[1:])),
             "travel": sum(float(r.get("travel_m") or 0.0) for r in rows),
             "coverage": float(rows[-1]["coverage"])}
        add_scans_to(m, rows, [float(r["coverage"]) for r in rows], LEVELS)
        trials.append(m)
    trials.sort(key=lambda m: (m["scene"], m["method"], setting_order(m["setting"]),
                               int(m["trial"])))
    return trials


def write_trials_csv(out, trials):
    """DIR/trials.csv: one row per trial; a level not reached leaves its fields empty."""
    def number(x, fmt):
        return "" if x is None else format(x, fmt)

    header = ["scene", "method", "alpha", "objective", "trial", "scans", "auc_cells_scans",
              "travel_m", "coverage"]
    for level in LEVELS:
        header += [f"scans_to_{round(100 * level)}", f"travel_to_{round(100 * level)}_m"]
    lines = [",".join(header)]
    for m in trials:
        fields = [m["scene"], m["method"], m["setting"][0], m["setting"][1], m["trial"],
                  str(m["scans"]), f"{m['auc']:.6g}", f"{m['travel']:.6g}", f"{m['coverage']:.6g}"]
        for level in LEVELS:
            fields += [number(m[("scans_to", level)], "d"),
                       number(m[("travel_to", level)], ".6g")]
        lines.append(",".join(fields))
    with open(os.path.join(out, "trials.csv"), "w") as f:
        f.write("\n".join(lines) + "\n")


def wilcoxon_p(differences):
    """Two-sided p-value of the Wilcoxon signed-rank test of the paired differences, zero
    differences dropped first (Wilcoxon's own treatment; dropping them here rather than through
    zero_method lets scipy use the exact distribution for up to 50 pairs, which it refuses when
    zeros are present); 1.0 when every difference is zero, None without differences or scipy."""
    if not differences:
        return None
    nonzero = [d for d in differences if d != 0]
    if not nonzero:
        return 1.0
    try:
        from scipy.stats import wilcoxon
    except ImportError:
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # ties and small samples: scipy says so, the p stands
        return float(wilcoxon(nonzero, alternative="two-sided").pvalue)


def median(values):
    v = sorted(values)
    n = len(v)
    return (v[n // 2] + v[(n - 1) // 2]) / 2


def paired_measures(budget):
    """(name, value of a trial's metrics or None to leave its pair out, format, the coverage
    level whose censored trials the row counts or None)."""
    measures = [("AUC [cells x scans]", lambda m: m["auc"], ".0f", None),
                ("travel [m]", lambda m: m["travel"], ".2f", None)]
    for level in LEVELS:
        pct = round(100 * level)
        measures.append((f"scans to {pct}%",
                         lambda m, lv=level: budget + 1 if m[("scans_to", lv)] is None
                         else m[("scans_to", lv)], ".1f", level))
    for level in LEVELS:
        pct = round(100 * level)
        measures.append((f"travel to {pct}% [m]", lambda m, lv=level: m[("travel_to", lv)], ".2f",
                         None))
    return measures


def paired_summary(trials, budget):
    """summary.md's lines comparing each method with greedy, trial by trial (pairs on scene and
    start: the same scene, the same start pose and the same sensor noise seed)."""
    lines = ["## Paired with greedy", "",
             "Each method against greedy on the same scene and start (a pair; scenes pooled):",
             "median of the differences (method - greedy), the ratio of the two means (method's",
             "mean / greedy's mean over the same pairs) and the p-value of a two-sided Wilcoxon",
             "signed-rank test of the differences (scipy.stats.wilcoxon on the nonzero differences:",
             "exact up to 50 pairs without ties; 1 when all are zero; '-' with no pairs). Scans to X% = the first scan whose coverage",
             "(the observed share of the observable surface, observable = seen by the candidate",
             f"views and starts together) reaches X%; a trial that never does within its {budget}",
             f"scans is censored and counts as {budget + 1} scans; travel to X% = the distance",
             "travelled up to and including that scan, and a pair in which either trial is",
             "censored is left out of it (its pairs column says how many are left). censored =",
             "trials of the method / of greedy that did not reach the level.", ""]
    greedy = {(m["scene"], m["trial"]): m for m in trials if m["method"] == "greedy"}
    if not greedy:
        return lines + ["No greedy trials in this sweep: nothing to pair with.", ""]
    lines += ["| method | measure | pairs | median difference | mean / greedy's |"
              " p (Wilcoxon, two-sided) | censored |",
              "|---|---|---|---|---|---|---|"]
    methods = sorted({(m["method"], m["setting"]) for m in trials if m["method"] != "greedy"},
                     key=lambda ms: (ms[0], setting_order(ms[1])))
    for method, setting in methods:
        mine = [m for m in trials if (m["method"], m["setting"]) == (method, setting)
                and (m["scene"], m["trial"]) in greedy]
        for name, value, fmt, level in paired_measures(budget):
            pairs = [(value(m), value(greedy[(m["scene"], m["trial"])])) for m in mine]
            pairs = [(a, b) for a, b in pairs if a is not None and b is not None]
            censored = ""
            if level is not None:
                own = sum(m[("scans_to", level)] is None for m in mine)
                theirs = sum(greedy[(m["scene"], m["trial"])][("scans_to", level)] is None
                             for m in mine)
                censored = f"{own} / {theirs}"
            if not pairs:
                lines.append(f"| {label(method, setting)} | {name} | 0 | - | - | - | {censored} |")
                continue
            differences = [a - b for a, b in pairs]
            mean_greedy = sum(b for _, b in pairs) / len(pairs)
            mean_own = sum(a for a, _ in pairs) / len(pairs)
            ratio = f"{mean_own / mean_greedy:.3f}" if mean_greedy != 0 else "-"
            p = wilcoxon_p(differences)
            p_text = "-" if p is None else f"{p:.2g}"
            lines.append(f"| {label(method, setting)} | {name} | {len(pairs)} |"
                         f" {format(median(differences), fmt)} | {ratio} | {p_text} |"
                         f" {censored} |")
    lines.append("")
    return lines


# Surface coverage levels (shares of the visible object surface, docs/yardstick.md).
SURFACE_LEVELS = (0.80, 0.90, 0.95)
ORACLE = "greedy-oracle"


VIEW_BUDGET = 10  # views, the start's scan included


def at_budget(ms):
    """Mean coverage after VIEW_BUDGET views over the trials that ran that many, as text."""
    values = [m["at10"] for m in ms if m.get("at10") is not None]
    return f"{100 * sum(values) / len(values):.1f}%" if values else "-"


def has_surface(rows):
    return any(r.get("surface_coverage") for r in rows)


def surface_metrics(g):
    """One dict per trial with surface coverage: the area above its surface-coverage curve
    (sum over scans 1..N of 1 - coverage after the scan [scans]; a trial that stopped early
    carried forward) and the area under it (sum of the coverage [scans]), its travel [m], final
    surface and raw coverage, and per level the first scan reaching it and the travel up to and
    including that scan (None: censored)."""
    trials = []
    for (scene, method, setting), trial, rows in trial_rows(g):
        if not all(r.get("surface_coverage") for r in rows):
            continue
        cov = [float(r["surface_coverage"]) for r in rows]
        m = {"scene": scene, "method": method, "setting": setting, "trial": trial,
             "aac": sum(1 - c for c in cov), "auc": sum(cov),
             "travel": sum(float(r.get("travel_m") or 0.0) for r in rows),
             "final": cov[-1], "raw": float(rows[-1].get("raw_surface_coverage") or "nan"),
             # PB-NBV's and ClutterNBV's budget: the coverage after 10 views, the start's
             # included (None: the trial took fewer).
             "at10": cov[VIEW_BUDGET - 1] if len(cov) >= VIEW_BUDGET else None}
        add_scans_to(m, rows, cov, SURFACE_LEVELS)
        trials.append(m)
    trials.sort(key=lambda m: (m["scene"], m["method"], setting_order(m["setting"]),
                               int(m["trial"])))
    return trials


def add_scans_to(m, rows, coverage, levels):
    """m[("scans_to", level)] and m[("travel_to", level)]: the first scan whose coverage reaches
    each level and the travel up to and including it [m]; None where the trial never does."""
    for level in levels:
        m[("scans_to", level)] = m[("travel_to", level)] = None
        travel = 0.0
        for r, c in zip(rows, coverage):
            travel += float(r.get("travel_m") or 0.0)
            if c >= level - 1e-12:
                m[("scans_to", level)] = int(r["scan"])
                m[("travel_to", level)] = travel
                break


def censored_median(values, budget):
    """Median of scans to a level, a censored trial (None) counted as budget + 1; '>N' when the
    median is censored, and how many of the trials were."""
    if not values:
        return "-"
    v = median([budget + 1 if x is None else x for x in values])
    censored = sum(x is None for x in values)
    text = f">{budget}" if v > budget else f"{v:g}"
    return f"{text} ({censored}/{len(values)} cens.)" if censored else text


def gap_shares(trials):
    """(method, setting) -> list over pairs (scene, start) of the share of the gap between
    greedy's and the greedy oracle's area above the curve that the method closes:
    (A_greedy - A_method) / (A_greedy - A_oracle); pairs where the oracle is not ahead of greedy
    (A_greedy - A_oracle <= 0) are left out. Also the pooled share over all pairs."""
    by = {(m["scene"], m["trial"], m["method"], m["setting"]): m for m in trials}
    greedy = {(m["scene"], m["trial"]): m for m in trials if m["method"] == "greedy"}
    oracle = {(m["scene"], m["trial"]): m for m in trials if m["method"] == ORACLE}
    shares, pooled = defaultdict(list), defaultdict(lambda: [0.0, 0.0])
    for (scene, trial, method, setting), m in by.items():
        pair = (scene, trial)
        if pair not in greedy or pair not in oracle:
            continue
        room = greedy[pair]["aac"] - oracle[pair]["aac"]
        closed = greedy[pair]["aac"] - m["aac"]
        pooled[(method, setting)][0] += closed
        pooled[(method, setting)][1] += room
        if room > 1e-12:
            shares[(method, setting)].append(closed / room)
    return shares, {k: (a / b if b > 1e-12 else None) for k, (a, b) in pooled.items()}


def pooled_surface_table(trials, budget, ref="greedy"):
    """Per method over the pairs (scene, start) where every method ran: mean AAC, its sum over
    `ref`'s, the pooled share of the gap between greedy and the greedy oracle closed, mean scans
    to each level (budget + 1 where not reached) and travel, each with the two-sided Wilcoxon p of
    the paired differences from `ref`'s (RESULTS.md's issue-37 tables)."""
    by = {}
    for m in trials:
        by.setdefault(label(m["method"], m["setting"]), {})[(m["scene"], m["trial"])] = m
    if "greedy" not in by or ref not in by:
        return []
    keys = set.intersection(*(set(d) for d in by.values()))
    if not keys:
        return []
    g, o = by[ref], by.get("greedy-oracle")
    total = lambda d, f: sum(f(d[k]) for k in keys)
    aac, travel = (lambda m: m["aac"]), (lambda m: m["travel"])
    to = lambda lv: (lambda m: m[("scans_to", lv)] or budget + 1)
    ga, ra, rt = total(by["greedy"], aac), total(g, aac), total(g, travel)
    lines = [f"### Every method over the same pairs, against {ref} (scenes pooled)", "",
             f"{len(keys)} pairs (scene, start). × {ref}'s = the ratio of the sums; p = two-sided",
             f"Wilcoxon signed-rank test of the paired differences from {ref}'s; gap closed =",
             "(greedy's AAC - the method's) / (greedy's - the oracle's), pooled; scans to X% =",
             f"mean, {budget + 1} where not reached.", "",
             f"| method | AAC [scans] | × {ref}'s | p | gap closed | " +
             " | ".join(f"scans to {round(100 * lv)}% | p" for lv in SURFACE_LEVELS) +
             f" | travel [m] | × {ref}'s | p | final | after 10 views |",
             "|---|---|---|---|---|" + "---|---|" * len(SURFACE_LEVELS) + "---|---|---|---|---|"]

    def p_of(d, f):
        p = wilcoxon_p([f(d[k]) - f(g[k]) for k in sorted(keys)])
        return "-" if d is g or p is None else f"{p:.2g}"

    for name in sorted(by, key=lambda n: total(by[n], aac)):
        d = by[name]
        gap = (f"{(ga - total(d, aac)) / (ga - total(o, aac)):.2f}"
               if o is not None and ga != total(o, aac) else "-")
        levels = " | ".join(f"{total(d, to(lv)) / len(keys):.2f} | {p_of(d, to(lv))}"
                            for lv in SURFACE_LEVELS)
        lines.append(f"| {name} | {total(d, aac) / len(keys):.3f} | {total(d, aac) / ra:.3f} |"
                     f" {p_of(d, aac)} | {gap} | {levels} | {total(d, travel) / len(keys):.2f} |"
                     f" {total(d, travel) / rt:.3f} | {p_of(d, travel)} |"
                     f" {100 * total(d, lambda m: m['final']) / len(keys):.1f}% |"
                     f" {at_budget([d[k] for k in keys])} |")
    return lines + [""]


def new_coverage_prediction(rows, visible_cells):
    """How each prediction recorded for the view a run took foretells the new covered cells of
    its scan (scans 2 on, the runs of the surface model, whose rows carry all three on the same
    poses; greedy's count only in a sweep run with --greedy-reference): predicted_gain (the surface gain), greedy_predicted_gain (greedy's count) and
    predicted_cells (the unobserved-voxel count). Per prediction: the one scale that fits it best
    (the median of actual / predicted) and the median error factor after it,
    exp(median |log(actual / (scale predicted))|)."""
    runs = {}
    for r in rows:
        if r["method"] == "surface" and r.get("surface_coverage"):
            runs.setdefault((r["scene"], r["trial"]), {})[int(r["scan"])] = r
    logs = {"predicted_gain": [], "greedy_predicted_gain": [], "predicted_cells": []}
    for (scene, _), by_scan in runs.items():
        for s in sorted(by_scan):
            if s - 1 not in by_scan or scene not in visible_cells:
                continue
            new = (float(by_scan[s]["surface_coverage"]) -
                   float(by_scan[s - 1]["surface_coverage"])) * visible_cells[scene]
            for column, values in logs.items():
                v = float(by_scan[s].get(column) or 0.0)
                if new >= 1 and v > 0:
                    values.append(math.log(new / v))
    if not logs["predicted_gain"]:
        return []
    lines = ["### Predicting a scan's new coverage (the surface model's runs)", "",
             "| prediction for the view taken | scans | scale | median error factor after it |",
             "|---|---|---|---|"]
    names = {"predicted_gain": "the surface gain", "greedy_predicted_gain": "greedy's count",
             "predicted_cells": "the unobserved-voxel count"}
    for column, values in logs.items():
        if not values:  # greedy's count: the sweep ran without --greedy-reference
            continue
        mid = median(values)
        spread = median([abs(x - mid) for x in values])
        lines.append(f"| {names[column]} | {len(values)} | {math.exp(mid):.3g} |"
                     f" {math.exp(spread):.3f} (±{100 * (math.exp(spread) - 1):.0f} %) |")
    return lines + [""]


def yardstick_field(out, field):
    """Per scene, `field` of each of the sweep's yardstick files (DIR/yardstick/SCENE.json)."""
    values = {}
    folder = os.path.join(out, "yardstick")
    if os.path.isdir(folder):
        for name in os.listdir(folder):
            if name.endswith(".json"):
                with open(os.path.join(folder, name)) as f:
                    values[name[:-5]] = field(json.load(f))
    return values


def visible_cells_of(out):
    """Per scene, the visible surface cells of the sweep's yardstick files."""
    return yardstick_field(out, lambda truth: truth["visible_cells"])


def truth_measures(out):
    """views_by_truth.py's measures of the sweep (each trial's views scored by their noise-free
    hit sets), or None without yardstick files."""
    if not os.path.isdir(os.path.join(out, "yardstick")):
        return None
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import views_by_truth
    rows, _ = views_by_truth.measures(out)
    return rows or None


def yardstick_starts(out):
    """Per scene, the number of starts of the sweep's yardstick files."""
    return yardstick_field(out, lambda truth: len(truth["starts"]))


def surface_summary(trials, budget, set_cover_rows, tolerance=1, starts=None,
                    truth_rows=None, tolerance_m=0.0):
    covered = (f"a cell covered once a point lies within {1e3 * tolerance_m:g} mm of it"
               if tolerance_m else
               "a cell covered once a point lies in it" if tolerance == 0 else
               "a cell covered once a point lies in it or in one of its 26 neighbours")
    if tolerance_m:
        tolerance = f"{1e3 * tolerance_m:g}mm"
    lines = ["## Surface coverage by scan points", "",
             "surface = the share of the visible object surface (the object surface cells that the",
             "candidate views and starts hit with noise-free scans; table excluded) covered by the",
             f"registered scan points, {covered} (docs/yardstick.md,",
             f"--coverage-tolerance {tolerance}); raw = the same share of all object surface cells.",
             "Both after the last scan, mean over trials; after 10 views = surface after scan 10",
             "(PB-NBV's and ClutterNBV's budget, the start's scan included), mean over trials.",
             "AAC = area above the surface-coverage",
             "curve, sum over scans 1..N of (1 - coverage) [scans], mean over trials (lower is",
             "better). gap closed = (AAC greedy - AAC method) / (AAC greedy - AAC greedy-oracle),",
             "median over the pairs (scene, start) where the oracle is ahead of greedy (pooled",
             "over pairs in the next table): 0 = greedy, 1 = the greedy oracle. scans to X% =",
             "the median over trials of the first scan reaching X%, a trial that never does within",
             f"its {budget} scans counted as {budget + 1} ('>{budget}' when the median is",
             "censored; cens. = censored trials); travel to X% = median distance up to and",
             "including that scan over the trials that reach it [m].", ""]
    shares, pooled = gap_shares(trials)
    scenes = sorted({m["scene"] for m in trials})
    for scene in scenes:
        lines += [f"### {scene}", "",
                  "| method | trials | surface | raw | after 10 views | AAC [scans] | gap closed | " +
                  " | ".join(f"scans to {round(100 * lv)}%" for lv in SURFACE_LEVELS) + " | " +
                  " | ".join(f"travel to {round(100 * lv)}% [m]" for lv in SURFACE_LEVELS) + " |",
                  "|---|---|---|---|---|---|---|" + "---|" * (2 * len(SURFACE_LEVELS))]
        mine = [m for m in trials if m["scene"] == scene]
        keys = sorted({(m["method"], m["setting"]) for m in mine},
                      key=lambda ms: (ms[0], setting_order(ms[1])))
        scene_shares, _ = gap_shares(mine)
        for method, setting in keys:
            ms = [m for m in mine if (m["method"], m["setting"]) == (method, setting)]
            n = len(ms)
            share = scene_shares.get((method, setting))
            share_text = f"{median(share):.2f}" if share else "-"
            cells = [censored_median([m[("scans_to", lv)] for m in ms], budget)
                     for lv in SURFACE_LEVELS]
            travel = []
            for lv in SURFACE_LEVELS:
                reached = [m[("travel_to", lv)] for m in ms if m[("travel_to", lv)] is not None]
                travel.append(f"{median(reached):.2f}" if reached else "-")
            lines.append(f"| {label(method, setting)} | {n} |"
                         f" {100 * sum(m['final'] for m in ms) / n:.1f}% |"
                         f" {100 * sum(m['raw'] for m in ms) / n:.1f}% | {at_budget(ms)} |"
                         f" {sum(m['aac'] for m in ms) / n:.2f} | {share_text} | " +
                         " | ".join(cells) + " | " + " | ".join(travel) + " |")
        lines.append("")
    lines += ["### Gap closed between greedy and the greedy oracle (scenes pooled)", "",
              "Per method: pairs (scene, start) with greedy and the oracle, the median and pooled",
              "share of the gap closed, the median difference of AAC from greedy's [scans] and the",
              "p-value of a two-sided Wilcoxon signed-rank test of those differences (as below).",
              "", "| method | pairs | gap closed (median) | gap closed (pooled) |"
              " AAC - greedy's (median) [scans] | p (Wilcoxon) |", "|---|---|---|---|---|---|"]
    greedy = {(m["scene"], m["trial"]): m for m in trials if m["method"] == "greedy"}
    for method, setting in sorted({(m["method"], m["setting"]) for m in trials
                                   if m["method"] != "greedy"},
                                  key=lambda ms: (ms[0], setting_order(ms[1]))):
        diffs = [m["aac"] - greedy[(m["scene"], m["trial"])]["aac"] for m in trials
                 if (m["method"], m["setting"]) == (method, setting)
                 and (m["scene"], m["trial"]) in greedy]
        share = shares.get((method, setting))
        whole = pooled.get((method, setting))
        p = wilcoxon_p(diffs)
        lines.append(f"| {label(method, setting)} | {len(diffs)} |"
                     f" {f'{median(share):.2f}' if share else '-'} |"
                     f" {f'{whole:.2f}' if whole is not None else '-'} |"
                     f" {f'{median(diffs):.2f}' if diffs else '-'} |"
                     f" {'-' if p is None else f'{p:.2g}'} |")
    lines.append("")
    lines += oracle_against_greedy(trials, budget)
    if set_cover_rows:
        lines += ["## The set-cover bound", "",
                  "Per scene, start and level of the visible surface (scripts/set_cover.py, on the",
                  "noise-free hit sets of DIR/yardstick/): the views the greedy oracle takes on",
                  "those hit sets, the fewest views that reach the level (set_cover.py: whether",
                  "one view fewer than the best cover found reaches it, by a branch and bound",
                  "over HiGHS relaxations of maximum coverage; its `solver` column says which",
                  "steps ran), the proven",
                  "lower bound and the relative gap (0 = proven the fewest), its time",
                  "[s], and the shortest tour from",
                  "the start through the chosen views [m] (exact up to 12 views, else nearest",
                  "neighbour + 2-opt); '-' = no set of views reaches the level from that start.",
                  "Views do not count the start: the scans to a level are views + 1.", "",
                  "| scene | start | level | greedy oracle views | set cover views | lower bound |"
                  " gap | status | time [s] | tour [m] | greedy oracle's tour [m] |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in set_cover_rows:
            lines.append(f"| {r['scene']} | {r['start']} | {r['level']}% |"
                         f" {r['greedy_views'] or '-'} | {r['set_cover_views'] or '-'} |"
                         f" {r['lower_bound'] or '-'} | {r['gap'] or '-'} | {r['status']} |"
                         f" {r['seconds'] or '-'} | {r['tour_m'] or '-'} |"
                         f" {r['greedy_tour_m'] or '-'} |")
        lines.append("")
        lines += optimum_ratios(trials, budget, set_cover_rows, starts or {}, truth_rows)
    return lines


def optimum_ratios(trials, budget, set_cover_rows, starts, truth_rows=None):
    """Issue 49: per method and level, the views each trial took to reach the level (its scans
    less the start's) divided by the fewest views from the same scene and start (set_cover.csv;
    a trial's start is its number mod the scene's starts); the greedy oracle on the true hit sets
    (set_cover.csv's greedy_views) beside them. A trial that never reaches the level counts its
    budget's views, a lower bound on its ratio ('censored'). `truth_rows` (views_by_truth.py's
    measures) add the same ratios by the trial's views' noise-free hit sets."""
    fewest = {(r["scene"], int(r["start"]), r["level"]): r for r in set_cover_rows
              if r["set_cover_views"] not in ("", "0")}
    if not fewest:
        return []
    levels = [lv for lv in SURFACE_LEVELS if any(k[2] == f"{100 * lv:g}" for k in fewest)]
    lines = ["### Views to each level against the fewest", "",
             "Per method and level: the mean over trials of (scans to the level - 1) / the fewest",
             "views from the same scene and start (set_cover.csv; proven = cases whose fewest is",
             "proven optimal, else the best cover found, so the ratio is then a lower bound), and",
             f"in brackets the trials that never reach the level within {budget} scans (counted as",
             f"{budget - 1} views, a lower bound too). The last row: the greedy oracle's order on",
             "the noise-free hit sets (set_cover.csv's greedy_views).", "",
             "Registered: by the run's registered scan points (scans.csv), which noise can",
             "carry into cells the noise-free scans miss, so a ratio below 1 is possible; by the",
             "truth: the same trial's views scored by their noise-free hit sets",
             "(views_by_truth.py), never below 1.", "",
             "| method | " + " | ".join(f"views to {round(100 * lv)}% / fewest, registered"
                                      for lv in levels)
             + "".join(f" | by the truth, {round(100 * lv)}%" for lv in levels if truth_rows)
             + " |", "|---|" + "---|" * len(levels) * (2 if truth_rows else 1)]
    keys = sorted({(m["method"], m["setting"]) for m in trials},
                  key=lambda ms: (ms[0], setting_order(ms[1])))

    def cell(ratios, censored):
        if not ratios:
            return "-"
        return f"{sum(ratios) / len(ratios):.2f} ({censored}/{len(ratios)} cens.)"

    def ratios_of(scans_of, lv, mine):
        ratios, censored = [], 0
        for m in mine:
            if m["scene"] not in starts:
                continue
            row = fewest.get((m["scene"], int(m["trial"]) % starts[m["scene"]], f"{100 * lv:g}"))
            if row is None:
                continue
            scans = scans_of(m, lv)
            censored += scans is None
            views = budget - 1 if scans is None else scans - 1
            ratios.append(views / int(row["set_cover_views"]))
        return cell(ratios, censored)

    for method, setting in keys:
        mine = [m for m in trials if (m["method"], m["setting"]) == (method, setting)]
        cells = [ratios_of(lambda m, lv: m[("scans_to", lv)], lv, mine) for lv in levels]
        if truth_rows:
            name = label(method, setting)
            by_truth = [r for r in truth_rows if r["label"] == name]
            cells += [ratios_of(lambda r, lv: r[lv] if r[lv] <= budget else None, lv, by_truth)
                      for lv in levels]
        lines.append(f"| {label(method, setting)} | " + " | ".join(cells) + " |")
    oracle = []
    for lv in levels:
        rows = [r for k, r in fewest.items() if k[2] == f"{100 * lv:g}"]
        ratios = [int(r["greedy_views"]) / int(r["set_cover_views"]) for r in rows]
        proven = sum(r["status"] == "proven" for r in rows)
        oracle.append(f"{sum(ratios) / len(ratios):.2f} ({proven}/{len(rows)} proven)")
    if truth_rows:
        oracle = ["-"] * len(levels) + oracle
    lines += ["| greedy oracle, true hit sets | " + " | ".join(oracle) + " |", ""]
    return lines


def oracle_against_greedy(trials, budget):
    """Issue 36's check over a sweep: the cases (scene, start, level) where the greedy oracle
    needed more scans than greedy to reach the level, a run that never does counted as
    budget + 1, and where either never reached it."""
    oracle = {(m["scene"], m["trial"]): m for m in trials if m["method"] == ORACLE}
    pairs = [(m, oracle[(m["scene"], m["trial"])]) for m in trials
             if m["method"] == "greedy" and (m["scene"], m["trial"]) in oracle]
    if not pairs:
        return []
    behind, never = [], {"greedy": 0, ORACLE: 0}
    for g, o in pairs:
        for lv in SURFACE_LEVELS:
            gs, os_ = (x[("scans_to", lv)] or budget + 1 for x in (g, o))
            never["greedy"] += gs > budget
            never[ORACLE] += os_ > budget
            if os_ > gs:
                behind.append(f"{g['scene']} start {g['trial']} to {round(100 * lv)}% "
                              f"({os_ if os_ <= budget else 'never'} against {gs})")
    cases = len(pairs) * len(SURFACE_LEVELS)
    levels = ", ".join(f"{round(100 * lv)}%" for lv in SURFACE_LEVELS)
    return ["### The greedy oracle against greedy, case by case", "",
            f"Cases (scene, start, level of {levels}): {cases}. The oracle needed more scans than"
            f" greedy in {len(behind)} of them" + (": " + "; ".join(behind) if behind else "") + ".",
            f"Never reached within {budget} scans: greedy {never['greedy']}, the oracle"
            f" {never[ORACLE]} of the {cases}.", ""]


def pareto(points):
    """The points (travel, auc, ...) no other point beats in both (less travel, more area),
    by travel."""
    front = []
    for p in sorted(points, key=lambda p: (p[0], -p[1])):
        if not front or p[1] > front[-1][1]:
            front.append(p)
    return front


def plot_coverage_travel(out, trials, candidate_set):
    """DIR/coverage_travel.png: per method, the mean area under the surface-coverage curve
    [scans] against the mean travel per trial [m], over every scene and start of the sweep's
    candidate set, with the Pareto front (less travel, more area)."""
    points = []
    for method, setting in sorted({(m["method"], m["setting"]) for m in trials},
                                  key=lambda ms: (ms[0], setting_order(ms[1]))):
        ms = [m for m in trials if (m["method"], m["setting"]) == (method, setting)]
        points.append((sum(m["travel"] for m in ms) / len(ms), sum(m["auc"] for m in ms) / len(ms),
                       method, setting))
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for travel, auc, method, setting in points:
        ax.plot(travel, auc, "o", color=COLOURS.get(method, "0.4"), label=label(method, setting))
    front = pareto(points)
    ax.plot([p[0] for p in front], [p[1] for p in front], "--s", color="0.5", lw=1, ms=11,
            mfc="none", label="Pareto front")
    ax.set_title(f"candidate set: {candidate_set}")
    ax.set_xlabel("mean travel per trial [m]")
    ax.set_ylabel("area under the surface-coverage curve [scans]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "coverage_travel.png"), dpi=110)
    plt.close(fig)
    return front


def read_set_cover(out):
    path = os.path.join(out, "set_cover.csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def sweep_setting(out, key, default):
    """A setting of the sweep (sweep.json), or `default` where it has none."""
    try:
        with open(os.path.join(out, "sweep.json")) as f:
            return json.load(f).get(key, default)
    except (OSError, ValueError):
        return default


def candidate_set(out):
    """The sweep's candidate set (sweep.json), or 'unknown'."""
    return sweep_setting(out, "candidates", "unknown")


def main(argv):
    global LEVELS
    args = argv[1:]
    against = []
    if len(args) == 3 and args[1] == "--against":
        against = args[2].split(",")
        args = args[:1]
    if len(args) == 3 and args[1] == "--levels":
        try:
            LEVELS = tuple(float(x) / 100 for x in args[2].split(","))
        except ValueError:
            sys.exit(f"plot_bench.py: --levels takes percentages p,q,..., got '{args[2]}'")
        if not LEVELS or not all(0 < x <= 1 for x in LEVELS):
            sys.exit(f"plot_bench.py: --levels must lie in (0, 100], got '{args[2]}'")
        args = args[:1]
    if len(args) != 1:
        sys.exit("usage: plot_bench.py DIR [--levels 90,95 | --against METHOD,...]")
    out = args[0]
    rows = load(os.path.join(out, "scans.csv"))
    scenes = sorted({r["scene"] for r in rows})
    g = grouped(rows)
    plot_unobserved(out, scenes, g)
    if "travel_m" in rows[0]:
        plot_unobserved_by_travel(out, scenes, g)
    plot_prediction_error(out, scenes, g)
    trials = trial_metrics(g)
    write_trials_csv(out, trials)
    budget = max(k for by_scan in g.values() for k in by_scan)
    extra = []
    if has_surface(rows):
        surface = surface_metrics(g)
        extra = surface_summary(surface, budget, read_set_cover(out),
                                # NOTE: a sweep from before the setting counted within one cell
                                sweep_setting(out, "coverage_tolerance", 1),
                                yardstick_starts(out), truth_measures(out),
                                sweep_setting(out, "coverage_tolerance_m", 0.0))
        for ref in ["greedy"] + against:
            extra += pooled_surface_table(surface, budget, ref)
        extra += new_coverage_prediction(rows, visible_cells_of(out))
        plot_coverage_travel(out, surface, candidate_set(out))
    summary(out, scenes, g, extra + paired_summary(trials, budget))


if __name__ == "__main__":
    main(sys.argv)
