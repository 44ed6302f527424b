#!/usr/bin/python3
"""How well would each way of choosing a have predicted the cells seen, on the same poses?

Usage: alpha_fit_study.py RUN_DIR [RUN_DIR ...]
Reads explore folders run with --alpha auto and --greedy-reference (run.json keeps, per scan, the view's expected cells
seen under every candidate a, taken before the scan: calibration_cells). For every scan from the
second on it scores, against the cells the scan really turned known:
- each fixed a of the fit's grid;
- the online fit (the a with the least recency-weighted |ln((E + 1) / (actual + 1))| over the
  scans before, E interpolated between the evaluated values of a as ObservabilityFit does, the
  first scan's calibration on the empty map included) for several recencies, and without the
  first scan (the prior for the second);
- the trend rule: the last scan's best a moved on by a damped step of its last change;
- the a chosen in hindsight for each scan (a bound on any rule that picks one a per scan);
- greedy's count on the same pose.
Prints the mean absolute error [cells] over scans 2.. per scene and overall.
"""
import json
import math
import sys
from collections import defaultdict


STEPS = 32  # search points per interval of the evaluated a values, as ObservabilityFit


def interpolate(cal, xs, x):
    """ln(E + 1) at x = ln(1 - a), piecewise linear between the evaluated values."""
    j = 0
    while j + 2 < len(xs) and x < xs[j + 1]:
        j += 1
    f = min(1.0, max(0.0, (x - xs[j]) / (xs[j + 1] - xs[j])))
    return (1 - f) * math.log1p(cal[j]) + f * math.log1p(cal[j + 1])


def fit_choice(history, xs, recency):
    """The x = ln(1 - a) the fit picks from (calibration, actual) pairs, oldest first; None if
    there are none."""
    if not history:
        return None
    grid = [xs[0]] + [xs[j] + (xs[j + 1] - xs[j]) * k / STEPS
                      for j in range(len(xs) - 1) for k in range(1, STEPS + 1)]
    best, best_err = None, None
    for x in grid:
        err = 0.0
        for cal, actual in history:
            err = recency * err + abs(interpolate(cal, xs, x) - math.log1p(actual))
        if best_err is None or err < best_err:
            best, best_err = x, err
    return best


def best_x(cal, actual, xs):
    """The x = ln(1 - a) whose interpolated E matches this one scan's outcome best."""
    return fit_choice([(cal, actual)], xs, 1.0)


def trend_choice(history, xs, damping):
    """The last scan's best x moved on by `damping` times its change since the scan before:
    the best a falls through a run, and a fit of the past lags it by a scan."""
    if not history:
        return None
    last = best_x(*history[-1], xs)
    if len(history) < 2:
        return last
    step = last - best_x(*history[-2], xs)
    return min(xs[0], max(xs[-1], last + damping * step))


def predicted(cal, xs, x):
    return math.expm1(interpolate(cal, xs, x))


def main(dirs):
    rows = defaultdict(lambda: defaultdict(list))  # scene -> rule -> errors
    for d in dirs:
        run = json.load(open(f"{d}/run.json"))
        scene = run["scene"]["name"]
        alphas = run["config"]["observability"]["alphas"]
        xs = [math.log1p(-a) for a in alphas]
        scans = run["scans"]
        history = []
        for s in scans:
            cal, actual = s.get("calibration_cells"), float(s["actual_gain"])
            if cal is None:
                continue
            if s["scan"] > 1:
                for j, a in enumerate(alphas):
                    rows[scene][f"fixed a={a}"].append(abs(cal[j] - actual))
                prior = math.log1p(-run["config"]["observability"]["prior"])
                for r in (0.0001, 0.25, 0.5, 1.0):
                    x = fit_choice(history, xs, r)
                    rows[scene][f"fit recency={r}"].append(abs(predicted(cal, xs, x) - actual))
                    x = fit_choice(history[1:], xs, r)
                    x = prior if x is None else x  # the second scan: the prior, the literal a
                    rows[scene][f"fit recency={r}, no scan-1"].append(
                        abs(predicted(cal, xs, x) - actual))
                for damping in (0.0, 0.5, 1.0):
                    x = trend_choice(history, xs, damping)
                    rows[scene][f"trend damping={damping}"].append(
                        abs(predicted(cal, xs, x) - actual))
                # Not a rule: the a that would have matched this very scan, chosen in hindsight.
                # It bounds what any way of choosing one a per scan can reach.
                x = best_x(cal, actual, xs)
                rows[scene]["hindsight a (bound, not a rule)"].append(
                    abs(predicted(cal, xs, x) - actual))
                if s["greedy_predicted_gain"] is not None:  # run without --greedy-reference
                    rows[scene]["greedy count"].append(
                        abs(float(s["greedy_predicted_gain"]) - actual))
                rows[scene]["run's own prediction"].append(abs(float(s["predicted_cells"]) - actual))
            history.append((cal, actual))
    rules = sorted({r for v in rows.values() for r in v})
    scenes = sorted(rows)
    print("| rule | " + " | ".join(scenes) + " | all |")
    print("|---|" + "---|" * (len(scenes) + 1))
    for rule in rules:
        cells = []
        everything = []
        for sc in scenes:
            e = rows[sc].get(rule, [])
            everything += e
            cells.append(f"{sum(e) / len(e):.0f}" if e else "-")
        print(f"| {rule} | " + " | ".join(cells) + f" | {sum(everything) / len(everything):.0f} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
