#!/usr/bin/python3
"""Draws `vantage ray` output: visibility and occupancy posterior along one ray (Figs. 3 and 5).

Usage: plot_ray.py RAY.csv OUT.png [TITLE]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

STATE_COLOURS = {"free": "#4caf50", "occupied": "#e53935", "unobserved": "#fdd835"}


def state(p):
    if p <= 0.4:
        return "free"
    if p >= 0.6:
        return "occupied"
    return "unobserved"


def main(argv):
    if len(argv) < 3:
        sys.exit("usage: plot_ray.py RAY.csv OUT.png [TITLE]")
    with open(argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_ray.py: {argv[1]} has no rows")
    cells = [int(r["cell"]) for r in rows]
    fig, (top, strip) = plt.subplots(
        2, 1, figsize=(8, 4.2), sharex=True, gridspec_kw={"height_ratios": [5, 1]})
    top.plot(cells, [float(r["visibility"]) for r in rows], "o-", ms=3, label="visibility p(x)")
    top.plot(cells, [float(r["posterior"]) for r in rows], "s-", ms=3, label="posterior p(o)")
    top.set_ylim(-0.05, 1.05)
    top.set_ylabel("probability")
    # NOTE: a cell's gain is information, in bits and possibly negative (a cell the scan is
    # expected to make less certain): its own axis, not the probabilities' [0, 1].
    bits = top.twinx()
    gains = [float(r["gain"]) for r in rows]
    bits.plot(cells, gains, ":", color="grey", label="gain [bits]")
    bits.axhline(0.0, color="grey", lw=0.5)
    low, high = min(0.0, min(gains)), max(0.0, max(gains))
    pad = 0.05 * max(high - low, 1e-6)
    bits.set_ylim(low - pad, high + pad)
    bits.set_ylabel("expected information gain [bits]")
    handles = top.get_legend_handles_labels()[0] + bits.get_legend_handles_labels()[0]
    top.legend(handles=handles, loc="best", fontsize=8)
    top.grid(alpha=0.3)
    if len(argv) > 3:
        top.set_title(argv[3])
    for c, r in zip(cells, rows):
        strip.add_patch(Rectangle((c - 0.5, 0), 1, 1, edgecolor="white",
                                  facecolor=STATE_COLOURS[state(float(r["occupancy"]))]))
    strip.set_xlim(cells[0] - 0.5, cells[-1] + 0.5)
    strip.set_ylim(0, 1)
    strip.set_yticks([])
    strip.set_xlabel("cell along the ray (green free, red occupied, yellow unobserved)")
    fig.tight_layout()
    fig.savefig(argv[2], dpi=120)
    return fig


if __name__ == "__main__":
    main(sys.argv)
