#!/usr/bin/python3
"""The price of motion: how the travel-ranked planners trade surface coverage for travel as
Latombe's lambda [1/m] changes (docs/decision.md, "The price of motion").

Each DIR is a `vantage bench tabletop` sweep run with one `--lambda`, on the same scenes, starts
and candidates; its travel-ranked methods (RANKING+GAIN, latombe, sequence) are one point per
lambda, every other method (greedy, greedy-oracle, surface) a reference point, taken from the
first DIR that has it. Prints a Markdown table (mean area above the surface-coverage curve [scans]
and mean travel per trial [m], each also as a multiple of greedy's pooled over the same trials
when greedy ran) and draws OUT: area under the coverage curve against travel, the Pareto front
(less travel, more area) drawn, each point labelled with its lambda.

    /usr/bin/python3 scripts/price_of_motion.py DIR [DIR ...] --out price_of_motion.png
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import plot_bench  # noqa: E402  (the sweep summary's readers and its Pareto front)

plt = plot_bench.plt


def travel_ranked(method):
    """Whether `method` weighs its gain by the travel to a view: Latombe's exp(-lambda d)."""
    return "+" in method or method in ("latombe", "sequence")


def sweep_trials(folder):
    """The sweep's lambda [1/m] and its trials' surface metrics (plot_bench.surface_metrics)."""
    rows = plot_bench.load(os.path.join(folder, "scans.csv"))
    if not plot_bench.has_surface(rows):
        sys.exit(f"price_of_motion.py: {folder}/scans.csv has no surface coverage")
    return plot_bench.sweep_setting(folder, "lambda", None), plot_bench.surface_metrics(
        plot_bench.grouped(rows))


def points(folders):
    """(name, lambda or None, trials) per point: a travel-ranked method per folder, every other
    method once."""
    out, seen = [], set()
    for folder in folders:
        lam, trials = sweep_trials(folder)
        for method in sorted({m["method"] for m in trials}):
            mine = [m for m in trials if m["method"] == method]
            if travel_ranked(method):
                out.append((method, lam, mine))
            elif method not in seen:
                seen.add(method)
                out.append((method, None, mine))
    return out


def pooled_ratio(mine, greedy, key):
    """Sum of `key` over `mine`'s trials over greedy's sum on the same (scene, trial) pairs;
    None without greedy on every one of them."""
    ref = {(m["scene"], m["trial"]): m[key] for m in greedy}
    pairs = [(m[key], ref.get((m["scene"], m["trial"]))) for m in mine]
    if not pairs or any(r is None for _, r in pairs) or sum(r for _, r in pairs) == 0:
        return None
    return sum(a for a, _ in pairs) / sum(r for _, r in pairs)


def table(pts):
    greedy = next((t for name, lam, t in pts if name == "greedy" and lam is None), [])
    lines = ["| method | lambda [1/m] | trials | AAC [scans] | × greedy's | travel [m] |"
             " × greedy's |",
             "|---|---|---|---|---|---|---|"]
    for name, lam, trials in sorted(pts, key=lambda p: (p[1] is not None, p[0], p[1] or 0)):
        n = len(trials)
        aac = sum(m["aac"] for m in trials) / n
        travel = sum(m["travel"] for m in trials) / n
        ratios = [pooled_ratio(trials, greedy, k) for k in ("aac", "travel")]
        cells = ["-" if r is None else f"{r:.3f}" for r in ratios]
        lines.append(f"| {name} | {'-' if lam is None else f'{lam:g}'} | {n} | {aac:.3f} | "
                     f"{cells[0]} | {travel:.2f} | {cells[1]} |")
    return lines


def plot(pts, path):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    xy = []
    for name, lam, trials in pts:
        n = len(trials)
        travel = sum(m["travel"] for m in trials) / n
        auc = sum(m["auc"] for m in trials) / n
        xy.append((travel, auc, name, lam))
    for index, name in enumerate(sorted({p[2] for p in xy})):
        mine = sorted((p for p in xy if p[2] == name), key=lambda p: p[3] or 0)
        # RANKING+GAIN takes its gain's colour, so that it is not taken for the ranking's own
        # method (latombe+surface beside latombe); a gain without one, its own from the cycle.
        colour = (plot_bench.COLOURS.get(name) or plot_bench.COLOURS.get(name.split("+")[-1])
                  or f"C{index % 10}")
        ax.plot([p[0] for p in mine], [p[1] for p in mine], "o-" if len(mine) > 1 else "o",
                color=colour, label=name)
        for travel, auc, _, lam in mine:
            if lam is not None:
                ax.annotate(f"λ={lam:g}", (travel, auc), fontsize=7, xytext=(4, 3),
                            textcoords="offset points")
    front = plot_bench.pareto(xy)
    ax.plot([p[0] for p in front], [p[1] for p in front], "--s", color="0.5", lw=1, ms=11,
            mfc="none", label="Pareto front")
    ax.set_xlabel("mean travel per trial [m]")
    ax.set_ylabel("area under the surface-coverage curve [scans]")
    ax.set_title("the price of motion: Latombe's λ")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return front


def main(argv):
    args = argv[1:]
    if "--out" not in args or args.index("--out") + 1 >= len(args):
        sys.exit("usage: price_of_motion.py DIR [DIR ...] --out FILE.png")
    k = args.index("--out")
    out, folders = args[k + 1], args[:k] + args[k + 2:]
    if not folders:
        sys.exit("usage: price_of_motion.py DIR [DIR ...] --out FILE.png")
    pts = points(folders)
    print("\n".join(table(pts)))
    front = plot(pts, out)
    print("\nPareto front (less travel, more area): " +
          ", ".join(f"{name}" + ("" if lam is None else f" λ={lam:g}")
                    for _, _, name, lam in front))


if __name__ == "__main__":
    main(sys.argv)
