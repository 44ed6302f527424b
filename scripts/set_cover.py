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
- lower_bound, gap: the proven lower bound on the number of views and the relative gap
  (set_cover_views - lower_bound) / set_cover_views; 0 when the cover is proven optimal.
- tour_m: the shortest path from the start through the chosen views (no return): exact (Held-Karp
  dynamic programme) up to 12 views, else nearest neighbour improved by 2-opt (tour_method says
  which); in the sweep's travel rule [m].
- views: the chosen candidate indices, space-separated.

The fewest views are found exactly, by a branch and bound on the integer program "fewest views
x_v in {0, 1} whose hits reach the cells still needed": the cells the start does not hit are
merged into groups hit by the same views (weighted by their number), a counting bound (k views
hit at most the sum of the k largest new-cell counts) gives the first k, and for k = that bound,
+1, ... a depth-first search proves that no k views reach the level, or finds k that do (the
fewest). A node's children are its views by the new cells each adds, most first, the t-th
excluding the t - 1 before it, and are cut where the k best counts left fall short (new cells only
shrink as views are added). Time limit per level: --time-limit seconds; at the limit the greedy
cover stands, with the k proven so far as its lower bound (status says so). SciPy's `milp`
(HiGHS) on the same program, with a continuous share per group, was tried first: its linear
relaxation is weak (its bound stayed at 1 view within 10 s on a 270-view hemisphere, RESULTS.md
issue 36), so it proved few covers at 95-99 %.
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


class _Groups:
    """The cells of V the start does not hit, merged by the set of views that hit them: a 0/1
    matrix of views by groups and each group's weight (its number of cells)."""

    def __init__(self, truth, start):
        import numpy as np
        covering = {}  # cell -> views that hit it
        start_hits = truth["starts"][start]
        for v, cells in enumerate(truth["views"]):
            for c in cells - start_hits:
                covering.setdefault(c, []).append(v)
        weights = {}
        for views in covering.values():
            weights[tuple(views)] = weights.get(tuple(views), 0) + 1
        keys = list(weights)
        self.hits = np.zeros((len(truth["views"]), len(keys)), dtype=np.float64)
        for g, views in enumerate(keys):
            self.hits[list(views), g] = 1.0
        self.weight = np.array([weights[k] for k in keys], dtype=np.float64)
        # A view whose groups all lie in another's is never needed: the other does as well.
        inside = self.hits @ self.hits.T  # groups two views share
        size = np.diag(inside)
        self.useful = np.ones(len(truth["views"]), dtype=bool)
        for v in range(len(size)):
            within = np.flatnonzero(inside[v] == size[v])
            # NOTE: of views with the same groups, the lowest index stays.
            if any(size[u] > size[v] or u < v for u in within if u != v and self.useful[u]):
                self.useful[v] = False


class _OutOfTime(Exception):
    pass


def _cover_of(groups, k, remaining, deadline):
    """Views, at most k, whose hits reach `remaining` cells, or None when no such set exists:
    a depth-first branch and bound. A node's children are its allowed views by their new cells,
    most first; the t-th child excludes the t - 1 before it (so each set is visited once). New
    cells only shrink as views are added, so a child t is skipped when its cells and the k - 1
    views after it that add the most once t is in fall short, and the children stop where the k
    best counts left do; the last two views are found among every pair at once. Raises
    _OutOfTime."""
    import numpy as np

    def search(allowed, open_weight, covered, k):
        if covered >= remaining:
            return []
        if k == 0:
            return None
        if time.monotonic() > deadline:
            raise _OutOfTime()
        index = np.flatnonzero(allowed)
        gain = groups.hits[index] @ open_weight
        order = np.argsort(-gain, kind="stable")
        index, gain = index[order], gain[order]
        keep = gain > 0
        index, gain = index[keep], gain[keep]
        if len(index) and covered + gain[0] >= remaining:
            return [int(index[0])]
        if k == 1 or len(index) < 2:
            return None
        # What view u adds after view t: what it adds now less the open cells both hit.
        hits = groups.hits[index]
        after = gain[None, :] - (hits * open_weight) @ hits.T
        after[np.tril_indices(len(index))] = -np.inf  # child t's sets take views after t only
        if k == 2:
            pair = gain[:, None] + after
            t, u = np.unravel_index(np.argmax(pair), pair.shape)
            if covered + pair[t, u] >= remaining:
                return [int(index[t]), int(index[u])]
            return None
        # Child t's bound: t's cells and the k - 1 views after it that add the most once t is in.
        best_after = -np.partition(-after, k - 2, axis=1)[:, :k - 1]
        reach = covered + gain + np.where(np.isfinite(best_after), best_after, 0.0).sum(axis=1)
        window = np.concatenate([[0.0], np.cumsum(gain)])
        allowed = allowed.copy()
        for t in range(len(index)):
            # The k best counts from t on bound every child from t on: stop.
            if covered + window[min(t + k, len(index))] - window[t] < remaining - 1e-9:
                return None
            allowed[index[t]] = False
            if reach[t] < remaining - 1e-9:
                continue
            view = index[t]
            found = search(allowed, open_weight * (1.0 - groups.hits[view]),
                           covered + gain[t], k - 1)
            if found is not None:
                return [int(view)] + found
        return None

    return search(groups.useful.copy(), groups.weight.copy(), 0.0, k)


def set_cover(truth, start, need, incumbent, time_limit):
    """(views, lower bound, status) of the fewest views whose hits with the start's reach `need`
    cells, never more than the incumbent (a feasible cover). Exact: a branch and bound proves
    that no k views reach the level for k = the counting bound, +1, ... until one does (the
    fewest) or the incumbent's size is reached (the incumbent is the fewest); at the time limit
    the incumbent stands and the lower bound is the k proven so far."""
    start_hits = truth["starts"][start]
    remaining = need - len(start_hits)
    if remaining <= 0:
        return [], 0, "start alone"
    counting = size_bound(truth, start, remaining)
    if counting >= len(incumbent):
        return list(incumbent), counting, "optimal (counting bound)"
    groups = _Groups(truth, start)
    deadline = time.monotonic() + time_limit
    k = counting
    try:
        while k < len(incumbent):
            found = _cover_of(groups, k, remaining, deadline)
            if found is not None:
                return sorted(found), k, "optimal (branch and bound)"
            k += 1
    except _OutOfTime:
        return list(incumbent), k, f"time limit: no cover of fewer than {k} views"
    return list(incumbent), k, "optimal (branch and bound)"


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
        bound = min(bound, len(views))
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
