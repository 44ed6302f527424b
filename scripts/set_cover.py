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
- solver: the steps that ran (below); seconds: their wall-clock time.
- tour_m: the shortest path from the start through the chosen views (no return): exact (Held-Karp
  dynamic programme) up to 12 views, else nearest neighbour improved by 2-opt (tour_method says
  which); in the sweep's travel rule [m].
- views: the chosen candidate indices, space-separated.

The integer program: the cells the start does not hit, merged into groups hit by the same views
(weighted by their number); x_v in {0, 1} per view, y_g in [0, 1] per group, y_g <= the sum of
x_v over the views hitting g, sum of w_g y_g >= the cells still needed; minimise the sum of x_v.
A view whose groups lie in another's is dropped (valid for the count). Its steps, each stopping
once the lower bound meets the best cover: the counting bound (k views hit at most the sum of
the k largest new-cell counts); swaps that look for a cover of one view fewer (heuristic, for the
upper bound); a branch and bound of our own for k <= 3 views (faster than the solver there); the
linear relaxation, rounded up; the integer program, with at most the best cover - 1 views. The
last two are solved by HiGHS through scipy.optimize.milp, their rows y_g <= ... added lazily
(the groups left out count as hit, so every bound holds). Time limit per level: --time-limit
seconds (wall clock), at which the best cover stands with the bound proven so far.
"""
import csv
import glob
import io
import json
import math
import os
import sys
import time

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
    """The cells of V the start does not hit, merged by the set of views that hit them: a sparse
    0/1 matrix of views by groups (`hits`) and each group's weight (its number of cells). `useful`
    marks the views that count: a view whose groups all lie in another's is dropped (of views
    with the same groups, the lowest index stays). That is valid for the number of views, not
    for the tour: the other view does as well."""

    def __init__(self, truth, start):
        import numpy as np
        from scipy import sparse
        covering = {}  # cell -> views that hit it
        start_hits = truth["starts"][start]
        for v, cells in enumerate(truth["views"]):
            for c in cells - start_hits:
                covering.setdefault(c, []).append(v)
        weights = {}
        for views in covering.values():
            weights[tuple(views)] = weights.get(tuple(views), 0) + 1
        keys = list(weights)
        rows = [v for views in keys for v in views]
        cols = [g for g, views in enumerate(keys) for _ in views]
        self.hits = sparse.csr_matrix((np.ones(len(rows)), (rows, cols)),
                                      shape=(len(truth["views"]), len(keys)))
        self.weight = np.array([weights[k] for k in keys], dtype=np.float64)
        inside = (self.hits @ self.hits.T).toarray()  # groups two views share
        size = np.diag(inside)
        self.useful = np.ones(len(truth["views"]), dtype=bool)
        for v in range(len(size)):
            within = np.flatnonzero(inside[v] == size[v])
            if any(size[u] > size[v] or u < v for u in within if u != v and self.useful[u]):
                self.useful[v] = False

    def covered(self, views):
        """The weight of the groups `views` hit [cells]."""
        import numpy as np
        if not views:
            return 0.0
        count = np.asarray(self.hits[list(views)].sum(axis=0)).ravel()
        return float(self.weight[count > 0].sum())


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
    dense = groups.hits.toarray()

    def search(allowed, open_weight, covered, k):
        if covered >= remaining:
            return []
        if k == 0:
            return None
        if time.monotonic() > deadline:
            raise _OutOfTime()
        index = np.flatnonzero(allowed)
        gain = dense[index] @ open_weight
        order = np.argsort(-gain, kind="stable")
        index, gain = index[order], gain[order]
        keep = gain > 0
        index, gain = index[keep], gain[keep]
        if len(index) and covered + gain[0] >= remaining:
            return [int(index[0])]
        if k == 1 or len(index) < 2:
            return None
        # What view u adds after view t: what it adds now less the open cells both hit.
        hits = dense[index]
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
            found = search(allowed, open_weight * (1.0 - dense[view]), covered + gain[t], k - 1)
            if found is not None:
                return [int(view)] + found
        return None

    return search(groups.useful.copy(), groups.weight.copy(), 0.0, k)


def _swap_search(groups, k, remaining, seed, deadline, patience=40):
    """k views whose hits reach `remaining` cells, or None: from `seed` (cut to k views, or
    filled greedily), the swap of a chosen view for another that adds the most, until the level
    is reached, no swap helps (then a random swap among the 20 views adding the most; seed 1)
    or `patience` swaps pass without a new best. A heuristic: it only lowers the upper bound."""
    import numpy as np
    rng = np.random.default_rng(1)
    hits, weight = groups.hits, groups.weight
    allowed = groups.useful
    chosen = [v for v in seed if allowed[v]][:k]
    best, since = -1.0, 0
    while since < patience:
        if time.monotonic() > deadline:
            return None
        count = (np.asarray(hits[chosen].sum(axis=0)).ravel() if chosen
                 else np.zeros(hits.shape[1]))
        covered = weight[count > 0].sum()
        if covered >= remaining:
            return sorted(chosen)
        if len(chosen) == k:
            best, since = (covered, 0) if covered > best else (best, since + 1)
        gain = hits @ (weight * (count == 0))
        gain[~allowed] = -1.0
        gain[chosen] = -1.0
        if len(chosen) < k:
            chosen.append(int(np.argmax(gain)))
            continue
        only = weight * (count == 1)
        mine = hits[chosen]
        # Swapping chosen a for b: what b adds, less what only a hit, plus what b hits of that.
        value = (gain[None, :] - (mine @ only)[:, None]
                 + (mine.multiply(only[None, :]) @ hits.T).toarray())
        value[:, ~allowed] = -np.inf
        value[:, chosen] = -np.inf
        a, b = np.unravel_index(np.argmax(value), value.shape)
        if value[a, b] <= 0:
            a = int(rng.integers(k))
            top = [int(v) for v in np.argsort(-gain)[:20] if v not in chosen and gain[v] > 0]
            if not top:
                return None
            b = int(rng.choice(top))
        chosen[a] = int(b)
    return None


def _model(groups, rows, remaining, lo, hi):
    """The integer program on the groups `rows` (the others count as hit: a relaxation) for
    scipy's milp: variables x (the useful views) then y (the rows' groups)."""
    import numpy as np
    from scipy import sparse
    from scipy.optimize import LinearConstraint
    views = np.flatnonzero(groups.useful)
    n, m = len(views), len(rows)
    part = groups.hits[views][:, rows]
    link = sparse.hstack([-part.T, sparse.identity(m)]).tocsr()  # y_g <= sum of its views' x
    need = remaining - groups.weight[np.setdiff1d(np.arange(len(groups.weight)), rows)].sum()
    constraints = [LinearConstraint(link, -np.inf, 0.0),
                   LinearConstraint(np.concatenate([np.zeros(n), groups.weight[rows]])[None, :],
                                    need, np.inf),
                   LinearConstraint(np.concatenate([np.ones(n), np.zeros(m)])[None, :], lo, hi)]
    cost = np.concatenate([np.ones(n), np.zeros(m)])
    integrality = np.concatenate([np.ones(n), np.zeros(m)])
    return views, cost, constraints, integrality


def _lp_bound(groups, remaining, rows, deadline):
    """(the linear relaxation's fewest views, the rows it needed), or None at the deadline. Rows
    are added where the relaxation's views hit a group less than once, the least hit first, at
    most max(300, half the rows) a round, until none is."""
    import numpy as np
    from scipy.optimize import milp, Bounds
    rows = np.array(sorted(rows), dtype=int)
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return None
        views, cost, constraints, integrality = _model(groups, rows, remaining, 0, np.inf)
        result = milp(cost, bounds=Bounds(0, 1), constraints=constraints,
                      options={"time_limit": left})
        if result.status != 0:
            return None
        x = np.zeros(groups.hits.shape[0])
        x[views] = result.x[:len(views)]
        reach = groups.hits.T @ x
        out = np.ones(len(reach), dtype=bool)
        out[rows] = False
        short = np.flatnonzero(out & (reach < 1 - 1e-9))
        if len(short) == 0:
            return result.fun, rows
        short = short[np.argsort(reach[short], kind="stable")[:max(300, len(rows) // 2)]]
        rows = np.union1d(rows, short)


def _milp(groups, remaining, rows, lo, hi, deadline):
    """(views, lower bound, proven) of the integer program: at most `hi` views whose hits
    reach `remaining` cells, at least `lo`; views None when there are none (proven: none exist,
    else the time ran out). Groups outside `rows` count as hit (a relaxation, so its bound holds);
    a solution that falls short on them adds those rows and the program is solved again."""
    import numpy as np
    from scipy.optimize import milp, Bounds
    rows = np.array(sorted(rows), dtype=int)
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return None, lo, False
        views, cost, constraints, integrality = _model(groups, rows, remaining, lo, hi)
        result = milp(cost, integrality=integrality, bounds=Bounds(0, 1),
                      constraints=constraints, options={"time_limit": left})
        if result.status == 2:
            return None, hi + 1, True
        bound = lo
        if result.mip_dual_bound is not None and np.isfinite(result.mip_dual_bound):
            bound = max(lo, math.ceil(result.mip_dual_bound - 1e-6))
        if result.x is None:
            return None, bound, False
        chosen = [int(v) for v, on in zip(views, result.x[:len(views)]) if on > 0.5]
        if groups.covered(chosen) >= remaining - 1e-9:
            return chosen, bound, result.status == 0
        count = np.asarray(groups.hits[chosen].sum(axis=0)).ravel()
        out = np.ones(len(count), dtype=bool)
        out[rows] = False
        rows = np.union1d(rows, np.flatnonzero(out & (count == 0)))


SOLVER = "HiGHS (scipy.optimize.milp)"


def set_cover(truth, start, need, incumbent, time_limit):
    """(views, lower bound, status, solver) of the fewest views whose hits with the start's
    reach `need` cells, never more than the incumbent (a feasible cover). Bounds, in order, each
    stopping as soon as the lower bound meets the best cover: the counting bound; swaps that
    find covers of fewer views; the branch and bound for k = 2 and 3 views; the linear
    relaxation; the integer program (HiGHS, via scipy.optimize.milp). Status `proven` or
    `time limit` (the lower bound is what was proven by then)."""
    import numpy as np
    start_hits = truth["starts"][start]
    remaining = need - len(start_hits)
    if remaining <= 0:
        return [], 0, "proven", "start alone"
    best = sorted(incumbent)
    lower = size_bound(truth, start, remaining)
    if lower >= len(best):
        return best, lower, "proven", "counting bound"
    deadline = time.monotonic() + time_limit
    groups = _Groups(truth, start)
    steps = []

    def done(step):
        steps.append(step)
        return lower >= len(best)

    # Upper bound: swaps, each k below the best cover, within a fifth of the time.
    search_end = time.monotonic() + 0.2 * time_limit
    while len(best) > lower and time.monotonic() < search_end:
        found = _swap_search(groups, len(best) - 1, remaining, best, search_end)
        if found is None:
            break
        best = found
    if done("swaps"):
        return best, lower, "proven", "counting bound + swaps"
    # Lower bound, small k: the branch and bound proves no 2 or 3 views do, quickly.
    try:
        while lower <= 3 and lower < len(best):
            found = _cover_of(groups, lower, remaining, min(deadline, time.monotonic() +
                                                            0.2 * time_limit))
            if found is not None:
                best = sorted(found)
                break
            lower += 1
    except _OutOfTime:
        pass
    if done("branch and bound"):
        return best, lower, "proven", " + ".join(steps)
    # The linear relaxation, from the groups the best cover leaves and the rarest 5 %.
    count = np.asarray(groups.hits[best].sum(axis=0)).ravel()
    degree = np.asarray(groups.hits[np.flatnonzero(groups.useful)].sum(axis=0)).ravel()
    rows = np.flatnonzero((count == 0) | (degree <= np.percentile(degree, 5)))
    relaxed = _lp_bound(groups, remaining, rows, deadline)
    if relaxed is not None:
        value, rows = relaxed
        lower = max(lower, math.ceil(value - 1e-6))
        if done("HiGHS LP"):
            return best, lower, "proven", " + ".join(steps)
    # The integer program: fewer views than the best cover, or the proof that none do.
    while len(best) > lower:
        found, bound, proven = _milp(groups, remaining, rows, lower, len(best) - 1, deadline)
        lower = max(lower, bound)
        if found is None:
            break
        best = sorted(found)
        if not proven:
            break
    steps.append("HiGHS MILP")
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
          "tour_m", "tour_method", "greedy_tour_m", "views"]
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
                             tour_m="", tour_method="", greedy_tour_m="", views=""))
            continue
        began = time.monotonic()
        views, bound, status, solver = set_cover(truth, start, need, greedy, time_limit)
        seconds = time.monotonic() - began
        length, method = tour(truth, start, views)
        gap = (len(views) - bound) / len(views) if views else 0.0
        rows.append(dict(base, greedy_views=len(greedy), set_cover_views=len(views),
                         lower_bound=bound, gap=f"{gap:.3g}", status=status, solver=solver,
                         seconds=f"{seconds:.3g}", tour_m=f"{length:.4g}", tour_method=method,
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
