#!/usr/bin/python3
"""Draws one exploration run (the folder `vantage explore` writes).

Usage: plot_run.py RUN_DIR
Writes RUN_DIR/unobserved.png (unobserved cells and coverage by scan) and RUN_DIR/map.png (top
view of the final map's occupied cells with the candidate views and the views taken).
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def yaw_of(quaternion_xyzw):
    x, y, z, w = quaternion_xyzw
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def plot_progress(run_dir, scans, run):
    x = [int(r["scan"]) for r in scans]
    fig, ax = plt.subplots(figsize=(6.4, 4))
    ax.plot(x, [int(r["unobserved"]) for r in scans], "o-", color="#c62828", label="unobserved")
    ax.set_xlabel("scan")
    ax.set_ylabel("unobserved cells")
    ax.grid(alpha=0.3)
    cov = ax.twinx()
    cov.plot(x, [100 * float(r["coverage"]) for r in scans], "s--", color="#1565c0",
             label="coverage")
    cov.set_ylabel("coverage of the observable surface [%]")
    cov.set_ylim(0, 100)
    handles = ax.get_legend_handles_labels()[0] + cov.get_legend_handles_labels()[0]
    ax.legend(handles, ["unobserved cells", "coverage"], loc="center right")
    cfg = run["config"]
    method = cfg["method"] + (f", a = {cfg['alpha']}" if cfg["method"] == "probabilistic" else "")
    ax.set_title(f"{run['scene']['name']}: {method}")
    fig.tight_layout()
    fig.savefig(os.path.join(run_dir, "unobserved.png"), dpi=120)
    plt.close(fig)


def plot_map(run_dir, run):
    cells = read_csv(os.path.join(run_dir, "map_cells.csv"))
    fig, ax = plt.subplots(figsize=(6.4, 6.4))
    if cells:
        xs = [float(c["x"]) for c in cells]
        ys = [float(c["y"]) for c in cells]
        zs = [float(c["z"]) for c in cells]
        order = sorted(range(len(zs)), key=lambda i: zs[i])  # the highest cells drawn on top
        sc = ax.scatter([xs[i] for i in order], [ys[i] for i in order],
                        c=[zs[i] for i in order], s=2, cmap="viridis", marker="s")
        fig.colorbar(sc, ax=ax, shrink=0.7, label="height of occupied cells [m]")
    g = run["scene"]["grid"]
    ox, oy = g["origin"][0], g["origin"][1]
    w, h = g["dims"][0] * g["resolution"], g["dims"][1] * g["resolution"]
    ax.add_patch(plt.Rectangle((ox, oy), w, h, fill=False, ls=":", color="grey"))
    for c in run["candidates"]:
        px, py = c["position"][0], c["position"][1]
        yaw = yaw_of(c["quaternion_xyzw"])
        ax.arrow(px, py, 0.12 * math.cos(yaw), 0.12 * math.sin(yaw), color="#bdbdbd",
                 width=0.004, head_width=0.03, length_includes_head=True)
    path = [s["pose"]["position"][:2] for s in run["scans"]]
    ax.plot([p[0] for p in path], [p[1] for p in path], "-", color="#e65100", lw=1.5)
    for s in run["scans"]:
        px, py = s["pose"]["position"][:2]
        yaw = yaw_of(s["pose"]["quaternion_xyzw"])
        ax.arrow(px, py, 0.2 * math.cos(yaw), 0.2 * math.sin(yaw), color="#e65100",
                 width=0.008, head_width=0.05, length_includes_head=True)
        ax.annotate(str(s["scan"]), (px, py), textcoords="offset points", xytext=(6, 6),
                    fontsize=9, color="#e65100", weight="bold")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{run['scene']['name']}: final map and the {len(path)} views taken")
    ax.grid(alpha=0.2)
    fig.tight_layout()
    fig.savefig(os.path.join(run_dir, "map.png"), dpi=120)
    plt.close(fig)


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: plot_run.py RUN_DIR")
    run_dir = argv[1]
    with open(os.path.join(run_dir, "run.json")) as f:
        run = json.load(f)
    scans = read_csv(os.path.join(run_dir, "scans.csv"))
    plot_progress(run_dir, scans, run)
    plot_map(run_dir, run)


if __name__ == "__main__":
    main(sys.argv)
