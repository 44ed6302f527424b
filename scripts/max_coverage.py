"""The most cells k candidate views can hit, decided exactly: the core of scripts/set_cover.py
(docs/yardstick.md, "The fewest views").

The fewest views that hit `need` cells is the least k whose maximum coverage reaches `need`, so
each k is a yes-or-no question: do some k views hit `need` cells? `Cells` holds one start's
instance (the cells it does not hit, merged into groups hit by the same views); `reach` answers
the question by a branch and bound whose bounds are the linear relaxation of maximum coverage
with k views, solved by HiGHS (scipy.optimize.linprog) in its dual form; `tabu` looks for k
views that do, a heuristic for the upper bound.

The bound. For multipliers u_g in [0, w_g] on the groups, any k views hit at most
    sum_g (w_g - u_g) + the sum of the k largest c_v,   c_v = sum of u_g over the groups v hits
(a group's w_g * [hit] is at most (w_g - u_g) + u_g * (the chosen views hitting it)). It holds
for every u, so a bound is recomputed from the u the solver returns and never trusts its
objective; the least of it over u is the relaxation's optimum. The dual form has one row per view
and one bounded column per group, and the groups are priced in as their rows come short
(covered less than once by the relaxation's views), so a relaxation costs milliseconds to a few
tenths of a second where the primal form (a row per group) took seconds to a minute.
"""
import time

import numpy as np
from scipy import sparse
from scipy.optimize import linprog

EPS = 1e-6  # below `need` by more than this, a bound refutes (coverages are integers)
ACTIVE = 1.5  # a group stays in the next relaxation while the views cover it less than this


class OutOfTime(Exception):
    pass


class Cells:
    """The cells of V a start does not hit, merged by the set of views that hit them: `hits`, a
    sparse 0/1 matrix of groups by views, and `weight`, each group's number of cells. `useful`
    marks the views that count: a view whose groups all lie in another's is dropped (of views
    with the same groups, the lowest index stays); valid for the number of views, not the tour."""

    def __init__(self, views, start_hits):
        covering = {}  # cell -> views that hit it
        for v, cells in enumerate(views):
            for c in cells - start_hits:
                covering.setdefault(c, []).append(v)
        weights = {}
        for key in map(tuple, covering.values()):
            weights[key] = weights.get(key, 0) + 1
        keys = list(weights)
        rows = [g for g, vs in enumerate(keys) for _ in vs]
        cols = [v for vs in keys for v in vs]
        full = sparse.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(keys), len(views)))
        self.weight = np.array([weights[k] for k in keys], dtype=np.float64)
        inside = (full.T @ full).toarray()  # groups two views share
        size = np.diag(inside)
        useful = np.ones(len(views), dtype=bool)
        for v in range(len(size)):
            within = np.flatnonzero(inside[v] == size[v])
            if any(size[u] > size[v] or u < v for u in within if u != v and useful[u]):
                useful[v] = False
        self.views = np.flatnonzero(useful)  # column j is candidate view views[j]
        self.hits = full[:, self.views].tocsr()  # groups x useful views
        self.by_view = self.hits.T.tocsr()  # views x groups
        self.of_view = self.hits.tocsc()

    def groups_of(self, j):
        """The groups column j hits."""
        return self.of_view.indices[self.of_view.indptr[j]:self.of_view.indptr[j + 1]]

    def covered(self, columns):
        """The weight of the groups `columns` hit [cells]."""
        if len(columns) == 0:
            return 0.0
        return float(self.weight[self.by_view[list(columns)].sum(axis=0).A1 > 0].sum())


def _relaxation(cells, open_groups, columns, k, active):
    """(u over all groups, x over `columns`) of the linear relaxation of maximum coverage by k of
    `columns` of the open groups, in dual form: minimise sum (w_g - u_g) + k mu + sum s_v subject
    to c_v(u) - mu - s_v <= 0, u in [0, w]. Groups outside `active` hold u = 0 until a solution
    covers them less than once (then they join and it is solved again). None if HiGHS fails."""
    hits, w = cells.hits, cells.weight
    part = hits[:, columns]
    act = np.flatnonzero(active & open_groups)
    while True:
        block = part[act].T.tocsr()
        n = len(columns)
        a = sparse.hstack([block, sparse.csr_matrix(-np.ones((n, 1))), -sparse.identity(n)])
        cost = np.concatenate([-np.ones(len(act)), [k], np.ones(n)])
        upper = np.concatenate([w[act], np.full(n + 1, np.inf)])
        result = linprog(cost, A_ub=a.tocsr(), b_ub=np.zeros(n),
                         bounds=np.column_stack([np.zeros(len(upper)), upper]),
                         method="highs-ds", options={"presolve": False})
        if result.status != 0:
            return None
        u = np.zeros(len(w))
        u[act] = np.clip(result.x[:len(act)], 0.0, w[act])
        x = -result.ineqlin.marginals
        short = open_groups & (part @ x < 1 - 1e-7)
        short[act] = False
        if not short.any():
            return u, x
        act = np.union1d(act, np.flatnonzero(short))


class Search:
    """Do k views hit `need` cells? A depth-first branch and bound on one view at a time (taken,
    then left out). At each node: the bound above from the multipliers it inherits; if that does
    not refute, the relaxation's own (its u; a view that, taken, would bring it below `need` is
    dropped below the node, and one of the best by c_v that, left out, would is taken: every
    solution below holds it; the next view to branch on is the one with the most of what the
    relaxation takes of it times the open cells it hits); with two views left, or no more views
    than are left, every choice is tried. Raises OutOfTime past `deadline` (time.monotonic())."""

    def __init__(self, cells, need, deadline):
        self.cells, self.need, self.deadline = cells, need, deadline
        self.nodes = 0
        self.relaxations = 0

    def bound(self, covered, open_groups, u, columns, k):
        """The bound for k more of `columns` on top of `covered` cells, and each column's c_v."""
        w, u = self.cells.weight, u * open_groups
        c = self.cells.by_view[columns] @ u
        if len(c) < k:
            return -np.inf, c
        top = -np.partition(-c, k - 1)[:k].sum()
        return covered + (w * open_groups).sum() - u.sum() + top, c

    def exact(self, covered, open_groups, columns, left):
        """The best of at most `left` (<= 2, or all) of `columns`, if it reaches `need`."""
        w, need = self.cells.weight, self.need
        block = self.cells.by_view[columns]
        if len(columns) <= left:
            hit = open_groups & (block.sum(axis=0).A1 > 0)
            if covered + w[hit].sum() >= need - EPS:
                return [int(j) for j in columns]
            return None
        gain = block @ (w * open_groups)
        if left == 1:
            j = int(np.argmax(gain))
            return [int(columns[j])] if covered + gain[j] >= need - EPS else None
        shared = ((block @ sparse.diags(w * open_groups)) @ block.T).toarray()
        pair = gain[:, None] + gain[None, :] - shared
        i, j = np.unravel_index(np.argmax(pair), pair.shape)
        if covered + pair[i, j] >= need - EPS:
            return sorted({int(columns[i]), int(columns[j])})
        return None

    def reach(self, k):
        """k columns whose groups weigh at least `need`, or None when none exist (proven)."""
        cells, w, need = self.cells, self.cells.weight, self.need
        everything = np.ones(len(w), dtype=bool)
        stack = [(0.0, everything, np.zeros(len(w)), np.arange(len(cells.views)), k, (),
                  everything, True)]
        while stack:
            covered, open_groups, u, columns, left, chosen, active, solve = stack.pop()
            self.nodes += 1
            if time.monotonic() > self.deadline:
                raise OutOfTime()
            if covered >= need - EPS:
                return list(chosen)
            if left == 0 or len(columns) == 0:
                continue
            if left <= 2 or len(columns) <= left:
                found = self.exact(covered, open_groups, columns, left)
                if found is not None:
                    return list(chosen) + found
                continue
            value, c = self.bound(covered, open_groups, u, columns, left)
            if value < need - EPS:
                continue
            relaxed = _relaxation(cells, open_groups, columns, left, active) if solve else None
            self.relaxations += solve
            if relaxed is None:
                x = c
            else:
                u, x = relaxed
                value, c = self.bound(covered, open_groups, u, columns, left)
                if value < need - EPS:
                    continue
            # A view outside the `left` best by c_v, taken, trades the left-th best c for its
            # own: where that refutes, no solution below this node holds it (reduced-cost
            # fixing); one of the best left out gives way to the next: where that refutes,
            # every solution below holds it.
            order = np.argsort(-c, kind="stable")
            kth, next_c = c[order[left - 1]], c[order[left]]
            keep = value - np.maximum(0.0, kth - c) >= need - EPS
            forced = np.zeros(len(columns), dtype=bool)
            forced[order[:left]] = value - c[order[:left]] + next_c < need - EPS
            if (forced & ~keep).any():
                continue
            if forced.any():
                picked = columns[forced]
                groups = np.unique(np.concatenate([cells.groups_of(j) for j in picked]))
                groups = groups[open_groups[groups]]
                taken = open_groups.copy()
                taken[groups] = False
                stack.append((covered + w[groups].sum(), taken, u, columns[keep & ~forced],
                              left - len(picked), chosen + tuple(int(j) for j in picked),
                              active, True))
                continue
            columns, x, c = columns[keep], x[keep], c[keep]
            if len(columns) <= left:
                stack.append((covered, open_groups, u, columns, left, chosen, active, False))
                continue
            if relaxed is not None:
                active = open_groups & (cells.hits[:, columns] @ x < ACTIVE)
            # NOTE: what the relaxation takes of a view times the open cells it hits
            # branched on fewer nodes than its share alone (docs/yardstick.md).
            score = x * (cells.by_view[columns] @ (w * open_groups))
            j = int(np.argmax(score))
            groups = cells.groups_of(columns[j])
            groups = groups[open_groups[groups]]
            rest = np.delete(columns, j)
            taken_groups = open_groups.copy()
            taken_groups[groups] = False
            stack.append((covered, open_groups, u, rest, left, chosen, active, True))
            stack.append((covered + w[groups].sum(), taken_groups, u, rest, left - 1,
                          chosen + (int(columns[j]),), active, True))
        return None


def relaxation_bound(cells, need, k):
    """The relaxation's bound on the cells k views hit (for tests and reports)."""
    everything = np.ones(len(cells.weight), dtype=bool)
    columns = np.arange(len(cells.views))
    relaxed = _relaxation(cells, everything, columns, k, everything)
    if relaxed is None:
        return np.inf
    u = relaxed[0]
    return Search(cells, need, np.inf).bound(0.0, everything, u, columns, k)[0]


def tabu(cells, k, need, seed, deadline, iterations=50, tenure=7):
    """k columns whose groups weigh at least `need`, or None: a tabu search over swaps. From
    `seed` (cut to k, filled greedily), each step the swap of a chosen column for another that
    leaves the most weight hit, among those not tabu (a column swapped out stays out for `tenure`
    + 0-4 steps, one swapped in stays in for tenure / 2) unless it beats the best; ties broken by
    a seeded random jitter; `iterations` steps at most. A heuristic: it only lowers the upper
    bound."""
    rng = np.random.default_rng(1)
    a = cells.by_view.toarray()
    w = cells.weight
    chosen = [int(j) for j in seed][:k]
    count = a[chosen].sum(axis=0) if chosen else np.zeros(a.shape[1])
    while len(chosen) < k:
        gain = a @ (w * (count == 0))
        gain[chosen] = -1
        chosen.append(int(np.argmax(gain)))
        count += a[chosen[-1]]
    value = best = w[count > 0].sum()
    best_set = list(chosen)
    until = np.zeros(a.shape[0], dtype=int)
    for step in range(iterations):
        if best >= need - EPS or time.monotonic() > deadline:
            break
        gain = a @ (w * (count == 0))
        only = w * (count == 1)
        mine = a[chosen]
        # Swapping chosen i for column j: what j adds, less what only i hit, plus what j hits of
        # that.
        swap = gain[None, :] - (mine @ only)[:, None] + (mine * only) @ a.T
        swap[:, chosen] = -np.inf
        allowed = (until <= step)[None, :] & (until[chosen] <= step)[:, None]
        swap = np.where(allowed | (value + swap > best), swap, -np.inf)
        swap += rng.random(swap.shape) * 1e-3
        i, j = np.unravel_index(np.argmax(swap), swap.shape)
        if not np.isfinite(swap[i, j]):
            break
        out = chosen[i]
        count += a[j] - a[out]
        chosen[i] = int(j)
        value = w[count > 0].sum()
        until[out] = step + tenure + int(rng.integers(0, 5))
        until[j] = step + tenure // 2
        if value > best:
            best, best_set = value, list(chosen)
    return sorted(best_set) if best >= need - EPS else None
