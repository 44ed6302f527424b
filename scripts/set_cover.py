#!/usr/bin/python3
"""The set-cover bound of a table-top sweep (issue 36, docs/yardstick.md): per scene and start,
the fewest candidate views that, with the start's own scan, hit a given share of the visible
object surface V, and the shortest tour from the start through them.

Usage: set_cover.py DIR [--levels 80,90,95,99] [--time-limit 20]
Reads DIR/yardstick/SCENE.json (written by `vantage bench`: each candidate's and start's
noise-free hit set as indices into V, and the travel between them [m]) and, when present,
DIR/scans.csv for the starts the sweep's trials used (else every start). Writes DIR/set_cover.csv
(whole or not at all), one row per scene, start and level:

- greedy_views: the greedy oracle on the true hit sets (each step the view adding the most cells
  of V not yet hit; ties to the shorter travel from the current view, then the lower index): the
  views it takes until the start's and its hits reach the level; empty when no set of views does.
- set_cover_views: the fewest views (an integer program, below); never more than greedy_views,
  which it starts from as its upper bound.
- lower_bound, gap: the solver's proven lower bound on the number of views and the relative gap
  (set_cover_views - lower_bound) / set_cover_views; 0 when the cover is proven optimal.
- tour_m: the shortest path from the start through the chosen views (no return): exact (Held-Karp
  dynamic programme) up to 12 views, else nearest neighbour improved by 2-opt (tour_method says
  which); in the sweep's travel rule [m].
- views: the chosen candidate indices, space-separated.

The integer program (SciPy's `milp`, HiGHS): a binary x_v per view and a continuous y_g in [0, 1]
per group g of cells of V not hit by the start that the same set of views hits (merged: weight
w_g = their number); minimise sum x_v subject to y_g <= sum of the x_v that hit g, sum w_g y_g >=
the cells still needed, and sum x_v <= greedy_views (the greedy oracle's cover as the incumbent's
bound). Time limit per level: --time-limit seconds; relative gap tolerance 0 (proof of optimality
asked for; the reported gap says what the limit left). The lower bound is the larger of the
solver's and a counting bound (k views hit at most the sum of the k largest new-cell counts);
when the counting bound meets the greedy cover, that cover is optimal and the solver is not run.
"""
import csv
import glob
import io
import json
import math
import os
import sys
import time

LEVELS = (0.80, 0.90, 0.95, 0.99)
EXACT_TOUR_VIEWS = 12


def load_truth(path):
    with open(path) as f:
        truth = json.load(f)
    truth["views"] = [set(v) for v in truth["views"]]
    truth["starts"] = [set(s) for s in truth["starts"]]
    return truth


def needed(truth, level):
    """Cells of V the level asks for (at least level * |V|)."""
    return math.ceil(level * truth["visible_cells"] - 1e-9)


def greedy_oracle(truth, start):
    """The greedy oracle's order of views from `start` on the true hit sets: a list of
    (view, cells hit so far after it), until no view adds a cell."""
    hit = set(truth["starts"][start])
    order = []
    taken = set()
    here = None  # the start
    while True:
        best, best_gain, best_travel = None, 0, math.inf
        for v, cells in enumerate(truth["views"]):
            if v in taken:
                continue
            gain = len(cells - hit)
            travel = (truth["travel_m"]["from_starts"][start][v] if here is None
                      else truth["travel_m"]["views"][here][v])
            if gain > best_gain or (gain == best_gain and gain > 0 and travel < best_travel):
                best, best_gain, best_travel = v, gain, travel
        if best is None:
            return order
        taken.add(best)
        hit |= truth["views"][best]
        here = best
        order.append((best, len(hit)))


def greedy_cover(order, start_cells, need):
    """The greedy oracle's views up to the first that reaches `need` cells, or None."""
    if start_cells >= need:
        return []
    for k, (_, cells) in enumerate(order):
        if cells >= need:
            return [v for v, _ in order[:k + 1]]
    return None


def size_bound(truth, start, remaining):
    """A lower bound on the views needed to hit `remaining` cells the start does not: k views
    hit at most the sum of their k largest new-cell counts."""
    sizes = sorted((len(v - truth["starts"][start]) for v in truth["views"]), reverse=True)
    total = 0
    for k, size in enumerate(sizes, 1):
        total += size
        if total >= remaining:
            return k
    return len(sizes) + 1


def set_cover(truth, start, need, incumbent, time_limit):
    """(views, lower bound, solver status) of the fewest views whose hits with the start's reach
    `need` cells, bounded by the incumbent (a feasible cover)."""
    import numpy as np
    from scipy.optimize import Bounds, LinearConstraint, milp
    from scipy.sparse import lil_matrix

    start_hits = truth["starts"][start]
    remaining = need - len(start_hits)
    if remaining <= 0:
        return [], 0.0, "start alone"
    counting = size_bound(truth, start, remaining)
    if counting >= len(incumbent):
        return list(incumbent), float(counting), "optimal (counting bound)"
    n = len(truth["views"])
    covering = {}  # cell -> views that hit it
    for v, cells in enumerate(truth["views"]):
        for c in cells - start_hits:
            covering.setdefault(c, []).append(v)
    groups = {}  # the set of views -> weight
    for views in covering.values():
        key = tuple(views)
        groups[key] = groups.get(key, 0) + 1
    keys = list(groups)
    m = len(keys)
    # Variables: x_0 .. x_{n-1}, y_0 .. y_{m-1}.
    c = np.concatenate([np.ones(n), np.zeros(m)])
    a = lil_matrix((m + 2, n + m))
    for g, views in enumerate(keys):
        a[g, n + g] = 1.0
        for v in views:
            a[g, v] = -1.0
    for g, key in enumerate(keys):
        a[m, n + g] = groups[key]
    for v in range(n):
        a[m + 1, v] = 1.0
    lower = np.concatenate([np.full(m, -np.inf), [remaining, 0]])
    upper = np.concatenate([np.zeros(m), [np.inf, len(incumbent)]])
    result = milp(c, constraints=LinearConstraint(a.tocsr(), lower, upper),
                  integrality=np.concatenate([np.ones(n), np.zeros(m)]), bounds=Bounds(0, 1),
                  options={"time_limit": time_limit, "mip_rel_gap": 0.0})
    bound = result.mip_dual_bound if getattr(result, "mip_dual_bound", None) is not None else 0.0
    bound = max(bound, float(counting))
    if result.x is None:
        return list(incumbent), bound, f"incumbent kept ({result.message.strip()})"
    chosen = [v for v in range(n) if result.x[v] > 0.5]
    if len(chosen) >= len(incumbent):
        chosen = list(incumbent)
    status = "optimal" if result.status == 0 else result.message.strip()
    return chosen, bound, status


def tour(truth, start, views):
    """(length [m], method) of the shortest path from `start` through `views`."""
    if not views:
        return 0.0, "none"
    d0 = truth["travel_m"]["from_starts"][start]
    d = truth["travel_m"]["views"]
    k = len(views)
    if k <= EXACT_TOUR_VIEWS:
        # Held-Karp: best[mask][j] = shortest path from the start through mask, ending at j.
        best = [[math.inf] * k for _ in range(1 << k)]
        for j in range(k):
            best[1 << j][j] = d0[views[j]]
        for mask in range(1, 1 << k):
            row = best[mask]
            for j in range(k):
                if row[j] == math.inf:
                    continue
                for i in range(k):
                    if mask & (1 << i):
                        continue
                    nxt = row[j] + d[views[j]][views[i]]
                    if nxt < best[mask | (1 << i)][i]:
                        best[mask | (1 << i)][i] = nxt
        return min(best[(1 << k) - 1]), "exact"
    path, left = [], list(views)
    here = None
    while left:
        nxt = min(left, key=lambda v: d0[v] if here is None else d[here][v])
        path.append(nxt)
        left.remove(nxt)
        here = nxt

    def length(p):
        return d0[p[0]] + sum(d[a][b] for a, b in zip(p, p[1:]))

    improved = True
    while improved:
        improved = False
        for i in range(len(path) - 1):
            for j in range(i + 1, len(path)):
                candidate = path[:i] + path[i:j + 1][::-1] + path[j + 1:]
                if length(candidate) < length(path) - 1e-12:
                    path, improved = candidate, True
    return length(path), "nearest neighbour + 2-opt"


def trial_starts(out, scene, starts):
    """The starts the sweep's trials of `scene` used (trial mod the number of starts)."""
    path = os.path.join(out, "scans.csv")
    if not os.path.exists(path):
        return list(range(starts))
    with open(path, newline="") as f:
        trials = {int(r["trial"]) for r in csv.DictReader(f) if r["scene"] == scene}
    return sorted({t % starts for t in trials})


HEADER = ["scene", "candidates", "start", "level", "visible_cells", "start_cells", "greedy_views",
          "set_cover_views", "lower_bound", "gap", "status", "seconds", "tour_m", "tour_method",
          "greedy_tour_m", "views"]


def rows_for(truth, start, levels, time_limit):
    order = greedy_oracle(truth, start)
    start_cells = len(truth["starts"][start])
    rows = []
    for level in levels:
        need = needed(truth, level)
        base = {"scene": truth["scene"], "candidates": truth["candidates"], "start": start,
                "level": f"{100 * level:g}", "visible_cells": truth["visible_cells"],
                "start_cells": start_cells}
        greedy = greedy_cover(order, start_cells, need)
        if greedy is None:
            rows.append(dict(base, status="not reachable from this start", greedy_views="",
                             set_cover_views="", lower_bound="", gap="", seconds="", tour_m="",
                             tour_method="", greedy_tour_m="", views=""))
            continue
        began = time.monotonic()
        views, bound, status = set_cover(truth, start, need, greedy, time_limit)
        seconds = time.monotonic() - began
        length, method = tour(truth, start, views)
        bound = min(math.ceil(bound - 1e-6), len(views)) if views else 0
        gap = (len(views) - bound) / len(views) if views else 0.0
        rows.append(dict(base, greedy_views=len(greedy), set_cover_views=len(views),
                         lower_bound=bound, gap=f"{gap:.3g}", status=status,
                         seconds=f"{seconds:.3g}", tour_m=f"{length:.4g}", tour_method=method,
                         greedy_tour_m=f"{tour(truth, start, greedy)[0]:.4g}",
                         views=" ".join(map(str, sorted(views)))))
    return rows


def main(argv):
    global LEVELS
    args = argv[1:]
    time_limit = 20.0
    out = None
    while args:
        a = args.pop(0)
        if a == "--levels" and args:
            LEVELS = tuple(float(x) / 100 for x in args.pop(0).split(","))
        elif a == "--time-limit" and args:
            time_limit = float(args.pop(0))
        elif out is None:
            out = a
        else:
            sys.exit("usage: set_cover.py DIR [--levels 80,90,95,99] [--time-limit 20]")
    if out is None:
        sys.exit("usage: set_cover.py DIR [--levels 80,90,95,99] [--time-limit 20]")
    files = sorted(glob.glob(os.path.join(out, "yardstick", "*.json")))
    if not files:
        sys.exit(f"set_cover.py: no {out}/yardstick/*.json (a table-top sweep writes them)")
    rows = []
    for path in files:
        truth = load_truth(path)
        for start in trial_starts(out, truth["scene"], len(truth["starts"])):
            rows += rows_for(truth, start, LEVELS, time_limit)
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=HEADER, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    target = os.path.join(out, "set_cover.csv")
    with open(target + ".tmp", "w") as f:
        f.write(text.getvalue())
    os.replace(target + ".tmp", target)
    print(f"set_cover.py: {len(rows)} rows; {target}")


if __name__ == "__main__":
    main(sys.argv)
