#!/usr/bin/python3
"""The fewest views of a sweep (issues 36 and 49, docs/yardstick.md): per scene, start and level,
the fewest candidate views that, with the start's own scan, hit a given share of the visible
object surface V, proven optimal where it can be, and the shortest tour from the start through
them.

Usage: set_cover.py DIR [--levels 80,90,95,99,full] [--time-limit 60] [--scenes A,B,...]
Reads DIR/yardstick/SCENE.json (written by `vantage bench`: each candidate's and start's
noise-free hit set as indices into V, and the travel between them [m]) and, when present,
DIR/scans.csv for the starts the sweep's trials used (else every start). Writes DIR/set_cover.csv
(whole or not at all), one row per scene, start and level (`full`: every cell of V the start and
the candidates hit, MA-SCVP's full cover; need_cells says how many):

- greedy_views: the greedy oracle on the true hit sets (each step the view adding the most cells
  of V not yet hit; ties to the shorter travel from the current view, then the lower index): the
  views it takes until the start's and its hits reach the level; empty when no set of views does.
- set_cover_views: the fewest views found; never more than greedy_views.
- lower_bound, gap, status: the proven lower bound on the number of views, the relative gap
  (set_cover_views - lower_bound) / set_cover_views, and `proven` (gap 0) or `time limit`.
- solver: the steps that ran (below); seconds: their wall-clock time; cpu_seconds: the CPU time
  of this process in them (on a shared machine, what the load left it).
- tour_m: the shortest path from the start through the chosen views (no return): exact (Held-Karp
  dynamic programme) up to 12 views, else nearest neighbour improved by 2-opt (tour_method says
  which); in the sweep's travel rule [m].
- views: the chosen candidate indices, space-separated.

The fewest views are the least k for which some k views reach the level: the cells the start
does not hit are merged into groups hit by the same views (weighted by their number; a view whose
groups lie in another's is dropped, valid for the count), and scripts/max_coverage.py decides
exactly whether the most cells k views hit reach the level, for k one fewer than the best cover
(if k views reach it, so do k + 1: a no for that k proves the cover the fewest): a branch and
bound over the linear relaxation of maximum coverage with k views (HiGHS through
scipy.optimize.linprog, in its dual form); a yes gives a cover of k views, and the question is
asked again. Before it, a tabu search over swaps looks for a cover of one view fewer than the
greedy oracle's (the upper bound), and the least k the root's relaxation does not refute
(bisected from the counting bound: k views hit at most the sum of the k largest new-cell counts)
is the lower bound until the search answers. Time limit per level: --time-limit seconds (wall
clock, the start's groups built within its first level's), at which the best cover stands with
the lower bound proven so far.
"""
import csv
import glob
import io
import json
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import max_coverage  # noqa: E402  (the yes-or-no question for each k)

FULL = "full"  # the level: every cell of V the start and the candidates hit
LEVELS = (0.80, 0.90, 0.95, 0.99, FULL)
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


def travel_between(truth, start, here, view):
    """The travel to `view` from view `here`, or from the start when `here` is None [m]."""
    return (truth["travel_m"]["from_starts"][start][view] if here is None
            else truth["travel_m"]["views"][here][view])


def greedy_oracle(truth, start, travel_weight=0.0):
    """The greedy oracle's order of views from `start` on the true hit sets: a list of
    (view, cells hit so far after it), until no view adds a cell. With a travel weight λ [1/m],
    each view's new cells are priced as González-Baños and Latombe price a gain, times
    e^(-λ travel) from where the last view stood: the oracle under a planner's price of motion."""
    hit = set(truth["starts"][start])
    order = []
    taken = set()
    here = None  # the start
    while True:
        best, best_score, best_travel = None, 0.0, math.inf
        for v, cells in enumerate(truth["views"]):
            if v in taken:
                continue
            gain = len(cells - hit)
            travel = travel_between(truth, start, here, v)
            score = gain * math.exp(-travel_weight * travel)
            if score > best_score or (score == best_score and gain > 0 and travel < best_travel):
                best, best_score, best_travel = v, score, travel
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


def set_cover(truth, start, need, incumbent, time_limit, cache=None):
    """(views, lower bound, status, solver) of the fewest views whose hits with the start's
    reach `need` cells, never more than the incumbent (a feasible cover). Steps, each stopping
    once the lower bound meets the best cover: the counting bound; the tabu search for a cover of
    one view fewer than the best (a fifth of the time at most); the least k the root's relaxation
    does not refute (bisected); then max_coverage.Search: do one view fewer than the best reach
    the level? No proves the best (every smaller k refuted with it), yes gives a smaller cover
    and the question again. Status `proven` or `time limit` (the lower bound is what was proven
    by then). `cache`: a dict that keeps the start's
    max_coverage.Cells for its other levels (built within the first level's time)."""
    start_hits = truth["starts"][start]
    remaining = need - len(start_hits)
    if remaining <= 0:
        return [], 0, "proven", "start alone"
    best = sorted(incumbent)
    lower = size_bound(truth, start, remaining)
    if lower >= len(best):
        return best, lower, "proven", "counting bound"
    began = time.monotonic()
    deadline = began + time_limit
    cache = {} if cache is None else cache
    if "cells" not in cache:
        cache["cells"] = max_coverage.Cells(truth["views"], start_hits)
    cells = cache["cells"]
    column = {int(v): j for j, v in enumerate(cells.views)}
    steps = ["counting bound"]
    # Upper bound: a cover of one view fewer, while one is found, within a fifth of the time.
    tabu_end = min(deadline, began + 0.2 * time_limit)
    while len(best) > lower and time.monotonic() < tabu_end:
        seed = [column[v] for v in best if v in column]
        found = max_coverage.tabu(cells, len(best) - 1, remaining, seed, tabu_end)
        if found is None:
            break
        best = sorted(int(cells.views[j]) for j in found)
        if "tabu" not in steps:
            steps.append("tabu")
    nodes = 0
    try:
        # k views that reach the level are k + 1 that do, so refuting one view fewer than the
        # best refutes every smaller k: the search asks that last; the bound until it answers
        # starts at the least k the root's relaxation does not refute (it grows with k: bisected).
        low, high = lower, len(best) - 1
        while low < high:
            mid = (low + high) // 2
            if max_coverage.relaxation_bound(cells, remaining, mid) < remaining - 1e-6:
                low = mid + 1
            else:
                high = mid
            if time.monotonic() > deadline:
                raise max_coverage.OutOfTime()
        lower = low
        # Below one fewer than the best, each k the search refutes raises the bound reported at
        # the time limit; those searches share a fifth of the time, then the last k has the rest.
        upward_end = time.monotonic() + 0.2 * time_limit
        while lower < len(best) - 1 and time.monotonic() < upward_end:
            search = max_coverage.Search(cells, remaining, min(deadline, upward_end))
            try:
                found = search.reach(lower)
            except max_coverage.OutOfTime:
                break
            finally:
                nodes += search.nodes
            if found is None:
                lower += 1
            else:
                best = sorted(int(cells.views[j]) for j in found)
        while lower < len(best):
            search = max_coverage.Search(cells, remaining, deadline)
            try:
                found = search.reach(len(best) - 1)
            finally:
                nodes += search.nodes
            if found is None:
                lower = len(best)
            else:
                best = sorted(int(cells.views[j]) for j in found)
    except max_coverage.OutOfTime:
        pass
    if nodes:
        steps.append(f"branch and bound over HiGHS relaxations ({nodes} nodes)")
    status = "proven" if lower >= len(best) else "time limit"
    return best, min(lower, len(best)), status, " + ".join(steps)


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


HEADER = ["scene", "candidates", "start", "level", "visible_cells", "start_cells", "need_cells",
          "greedy_views", "set_cover_views", "lower_bound", "gap", "status", "solver", "seconds",
          "cpu_seconds", "tour_m", "tour_method", "greedy_tour_m", "views"]
USAGE = ("usage: set_cover.py DIR [--levels 80,90,95,99,full] [--time-limit 60] "
         "[--scenes A,B,...]")


def parse_levels(text):
    """Levels as shares of V, or FULL; exits on anything else."""
    levels = []
    for item in text.split(","):
        if item == "full":
            levels.append(FULL)
            continue
        try:
            level = float(item) / 100
        except ValueError:
            level = -1.0
        if not 0 < level <= 1:
            sys.exit(f"set_cover.py: --levels takes percentages in (0, 100] or 'full', "
                     f"got '{item}'")
        levels.append(level)
    return tuple(levels)


def reachable(truth, start):
    """The cells of V the start and the candidates hit together: the full cover's need."""
    return len(set(truth["starts"][start]).union(*truth["views"]))


def rows_for(truth, start, levels, time_limit):
    order = greedy_oracle(truth, start)
    start_cells = len(truth["starts"][start])
    rows = []
    cache = {}
    for level in levels:
        need = reachable(truth, start) if level == FULL else needed(truth, level)
        base = {"scene": truth["scene"], "candidates": truth["candidates"], "start": start,
                "level": level if level == FULL else f"{100 * level:g}",
                "visible_cells": truth["visible_cells"], "start_cells": start_cells,
                "need_cells": need}
        greedy = greedy_cover(order, start_cells, need)
        if greedy is None:
            rows.append(dict(base, status="not reachable from this start", greedy_views="",
                             set_cover_views="", lower_bound="", gap="", solver="", seconds="",
                             cpu_seconds="", tour_m="", tour_method="", greedy_tour_m="",
                             views=""))
            continue
        began, cpu = time.monotonic(), time.process_time()
        views, bound, status, solver = set_cover(truth, start, need, greedy, time_limit, cache)
        seconds, cpu = time.monotonic() - began, time.process_time() - cpu
        length, method = tour(truth, start, views)
        gap = (len(views) - bound) / len(views) if views else 0.0
        rows.append(dict(base, greedy_views=len(greedy), set_cover_views=len(views),
                         lower_bound=bound, gap=f"{gap:.3g}", status=status, solver=solver,
                         seconds=f"{seconds:.3g}", cpu_seconds=f"{cpu:.3g}",
                         tour_m=f"{length:.4g}", tour_method=method,
                         greedy_tour_m=f"{tour(truth, start, greedy)[0]:.4g}",
                         views=" ".join(map(str, sorted(views)))))
    return rows


def main(argv):
    args = argv[1:]
    levels = LEVELS
    time_limit = 60.0
    scenes = None
    out = None
    while args:
        a = args.pop(0)
        if a == "--levels" and args:
            levels = parse_levels(args.pop(0))
        elif a == "--time-limit" and args:
            try:
                time_limit = float(args.pop(0))
            except ValueError:
                sys.exit(USAGE)
        elif a == "--scenes" and args:
            scenes = set(args.pop(0).split(","))
        elif out is None and not a.startswith("--"):
            out = a
        else:
            sys.exit(USAGE)
    if out is None:
        sys.exit(USAGE)
    files = sorted(glob.glob(os.path.join(out, "yardstick", "*.json")))
    if not files:
        sys.exit(f"set_cover.py: no {out}/yardstick/*.json (a table-top sweep writes them)")
    rows = []
    for path in files:
        truth = load_truth(path)
        if scenes is not None and truth["scene"] not in scenes:
            continue
        for start in trial_starts(out, truth["scene"], len(truth["starts"])):
            rows += rows_for(truth, start, levels, time_limit)
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=HEADER, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    target = os.path.join(out, "set_cover.csv")
    with open(target + ".tmp", "w") as f:
        f.write(text.getvalue())
    os.replace(target + ".tmp", target)
    proven = sum(r["status"] == "proven" for r in rows)
    print(f"set_cover.py: {len(rows)} rows, {proven} proven; {target}")


if __name__ == "__main__":
    main(sys.argv)
