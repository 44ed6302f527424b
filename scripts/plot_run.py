#!/usr/bin/python3
"""Draws one exploration run (the folder `vantage explore` writes) or one plan (`vantage plan`).

Usage: plot_run.py RUN_DIR
For an exploration, writes RUN_DIR/unobserved.png (unobserved cells and coverage by scan; for an
office also unobserved cells by distance travelled) and RUN_DIR/map.png: on a table top, a top
view of the final map (occupied and unobserved cells) with the candidate views and the views
taken; in an office, a top view of the explored floor (seen free space, obstacles, rooms) with the
path driven and the stops, and the goals the robot could not reach (fallbacks, paper section
5.3.1).
For a plan (RUN_DIR holds plan.json), writes RUN_DIR/map.png: a top view of the map (occupied and
unobserved cells), the candidate views coloured by their predicted gain, the chosen view and the
robot.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import Normalize  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from plot_top_view import draw_top_view  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def yaw_of(quaternion_xyzw):
    x, y, z, w = quaternion_xyzw
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def plot_progress(run_dir, scans, run):
    fig = progress_figure(scans, run)
    fig.savefig(os.path.join(run_dir, "unobserved.png"), dpi=120)
    plt.close(fig)


def progress_figure(scans, run):
    """unobserved.png: unobserved cells and coverage by scan (office: also by distance)."""
    office = run["scene"].get("kind") == "office"
    x = [int(r["scan"]) for r in scans]
    fig, axes = plt.subplots(1, 2 if office else 1, figsize=(11.5 if office else 6.4, 4),
                             squeeze=False)
    ax = axes[0][0]
    ax.plot(x, [int(r["unobserved"]) for r in scans], "o-", color="#c62828", label="unobserved")
    ax.set_xlabel("stop (a 360-degree sweep each)" if office else "scan")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))  # no scan 1.5
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
    if office:
        travel, total = [], 0.0
        for r in scans:
            total += float(r.get("travel_m") or 0.0)
            travel.append(total)
        by = axes[0][1]
        by.plot(travel, [int(r["unobserved"]) for r in scans], "o-", color="#c62828")
        for r, d in zip(scans, travel):
            if r.get("fallback") == "1":
                by.plot([d], [int(r["unobserved"])], "x", color="black", ms=8)
        by.set_xlabel("distance travelled [m] (x: a fallback stop)")
        by.set_ylabel("unobserved cells")
        by.grid(alpha=0.3)
        by.set_title(f"{total:.1f} m in {len(scans)} stops")
    fig.tight_layout()
    return fig


def read_floor_map(path):
    with open(path) as f:
        header = f.readline().split()
        ox, oy, res = (float(v) for v in header[:3])
        nx, ny = int(header[3]), int(header[4])
        rows = [line.rstrip("\n").ljust(nx) for line in f]
    codes = {" ": 0, ".": 1, "#": 2}
    image = [[codes.get(ch, 0) for ch in row[:nx]] for row in rows[:ny]]
    return image, (ox, ox + nx * res, oy, oy + ny * res)


def plot_office_map(run_dir, run):
    from matplotlib.colors import ListedColormap

    image, extent = read_floor_map(os.path.join(run_dir, "floor_map.txt"))
    w, h = extent[1] - extent[0], extent[3] - extent[2]
    fig, ax = plt.subplots(figsize=(min(14, 3 + 0.55 * w), min(14, 1.2 + 0.55 * h)))
    ax.imshow(image, origin="lower", extent=extent, interpolation="nearest",
              cmap=ListedColormap(["#eeeeee", "#bbdefb", "#37474f"]), vmin=0, vmax=2)
    for room in run["scene"].get("rooms", []):
        (x0, y0), (x1, y1) = room["min"], room["max"]
        ax.add_patch(plt.Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ls=":", lw=0.8,
                                   color="#616161"))
        ax.annotate(room["name"], ((x0 + x1) / 2, y1 - 0.25), ha="center", va="top",
                    fontsize=7, color="#616161")
    for s in run["scans"]:
        path = s.get("path", [])
        if path:
            ax.plot([p[0] for p in path], [p[1] for p in path], "-", color="#e65100", lw=1.4)
    for c in run.get("candidates", []):
        ax.plot(c["position"][0], c["position"][1], "+", color="#7b1fa2", ms=6)
    for s in run["scans"]:
        px, py = s["pose"]["position"][:2]
        first = s["scan"] == 1
        ax.plot(px, py, "o", ms=9 if first else 6, color="#2e7d32" if first else "#e65100",
                mec="black", mew=0.6)
        ax.annotate(str(s["scan"]), (px, py), textcoords="offset points", xytext=(5, 5),
                    fontsize=8, color="black", weight="bold")
        if s.get("fallback") and s.get("goal"):
            gx, gy = s["goal"][:2]
            ax.plot(gx, gy, "x", color="#b71c1c", ms=8, mew=2)
            ax.plot([px, gx], [py, gy], ":", color="#b71c1c", lw=1)
    handles = [plt.Line2D([], [], color="#e65100", lw=1.4, label="path driven"),
               plt.Line2D([], [], marker="o", ls="", color="#e65100", mec="black",
                          label="stops (360-degree sweeps)"),
               plt.Line2D([], [], marker="o", ls="", ms=9, color="#2e7d32", mec="black",
                          label="start"),
               plt.Line2D([], [], marker="x", ls="", color="#b71c1c", mew=2,
                          label="unreachable goal (fallback)"),
               plt.Line2D([], [], marker="+", ls="", color="#7b1fa2",
                          label="frontier stops left"),
               plt.Rectangle((0, 0), 1, 1, color="#eeeeee", ec="#bdbdbd",
                             label="not seen at sensor height (unobserved)"),
               plt.Rectangle((0, 0), 1, 1, color="#bbdefb", label="seen free at sensor height"),
               plt.Rectangle((0, 0), 1, 1, color="#37474f", label="obstacle (robot's band)")]
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_xlim(extent[0], extent[1])
    ax.set_ylim(extent[2], extent[3])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    cfg = run["config"]
    method = cfg["method"] + (f", a = {cfg['alpha']}" if cfg["method"] == "probabilistic" else "")
    travel = sum(float(s.get("travel_m", 0.0)) for s in run["scans"])
    ax.set_title(f"{run['scene']['name']}, {method}: {len(run['scans'])} stops, {travel:.1f} m")
    fig.tight_layout()
    fig.savefig(os.path.join(run_dir, "map.png"), dpi=120)
    plt.close(fig)


def plot_map(run_dir, run):
    fig, ax = plt.subplots(figsize=(9.0, 6.4))
    handles = draw_top_view(ax, os.path.join(run_dir, "map_top.csv"), fig)
    g = run["scene"]["grid"]
    ox, oy = g["origin"][0], g["origin"][1]
    w, h = g["dims"][0] * g["resolution"], g["dims"][1] * g["resolution"]
    for c in run["candidates"]:
        px, py = c["position"][0], c["position"][1]
        yaw = yaw_of(c["quaternion_xyzw"])
        ax.arrow(px, py, 0.12 * math.cos(yaw), 0.12 * math.sin(yaw), color="#bdbdbd",
                 width=0.004, head_width=0.03, length_includes_head=True)
    path = [s["pose"]["position"][:2] for s in run["scans"]]
    # The robot walks around the table, the shorter way along the ring: draw arcs, not chords.
    cx, cy = ox + w / 2, oy + h / 2
    walk_x, walk_y = [], []
    for (x0, y0), (x1, y1) in zip(path, path[1:]):
        a0, a1 = math.atan2(y0 - cy, x0 - cx), math.atan2(y1 - cy, x1 - cx)
        r0, r1 = math.hypot(x0 - cx, y0 - cy), math.hypot(x1 - cx, y1 - cy)
        da = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi
        for k in range(41):
            t = k / 40
            walk_x.append(cx + (r0 + t * (r1 - r0)) * math.cos(a0 + t * da))
            walk_y.append(cy + (r0 + t * (r1 - r0)) * math.sin(a0 + t * da))
    ax.plot(walk_x, walk_y, "-", color="#e65100", lw=1.5, alpha=0.7)
    labels = {}  # scans taken from the same place share one label
    for s in run["scans"]:
        px, py = s["pose"]["position"][:2]
        yaw = yaw_of(s["pose"]["quaternion_xyzw"])
        ax.arrow(px, py, 0.2 * math.cos(yaw), 0.2 * math.sin(yaw), color="#e65100",
                 width=0.008, head_width=0.05, length_includes_head=True)
        labels.setdefault((round(px, 2), round(py, 2)), []).append(str(s["scan"]))
    for (px, py), scans in labels.items():
        # Outward from the table, so that labels do not cover the map.
        ux, uy = px - cx, py - cy
        norm = math.hypot(ux, uy) or 1.0
        ax.annotate(",".join(scans), (px, py), textcoords="offset points",
                    xytext=(14 * ux / norm, 14 * uy / norm), ha="center", va="center",
                    fontsize=9, color="#e65100", weight="bold")
    handles += [plt.Line2D([], [], marker=r"$\rightarrow$", ls="", ms=10, color="#bdbdbd",
                           label="candidate views"),
                plt.Line2D([], [], marker=r"$\rightarrow$", ls="", ms=12, color="#e65100",
                           label="views taken (number: scan)"),
                plt.Line2D([], [], color="#e65100", lw=1.5, alpha=0.7, label="walk")]
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{run['scene']['name']}: final map and the {len(path)} views taken")
    ax.grid(alpha=0.2)
    legend_below(fig, ax, handles, ncol=3)
    fig.savefig(os.path.join(run_dir, "map.png"), dpi=120)
    plt.close(fig)


# The methods that predict with a visibility model: they rank by their objective, bits or cells.
OBSERVABILITY_METHODS = ("probabilistic", "survival")


def ranking_of(doc, method):
    """(key, unit, what) of the number a method ranks a plan's candidates by: plan.json's `score`
    in its unit and what it is. plan.json before `units.score` followed the objective said
    "bits" for the survival reading's score, which is its expected cells seen: for the methods
    with a visibility model the objective names the unit."""
    units = doc.get("units", {})
    if not all("score" in c for c in doc.get("candidates", [])):  # an older plan.json
        return "predicted_gain", units.get("predicted_gain", ""), "predicted gain"
    unit = units.get("score", units.get("predicted_gain", ""))
    if method in OBSERVABILITY_METHODS and doc.get("objective") in ("bits", "cells"):
        unit = doc["objective"]
    what = {"latombe": "greedy gain x exp(-lambda x travel)", "yamauchi": "minus the travel",
            "random": "score (the choice is drawn at random)"}.get(method, "score")
    if method in OBSERVABILITY_METHODS:
        what = "expected cells seen" if unit == "cells" else "expected information gain"
    return "score", unit, what


def format_number(x, unit):
    """A number as `vantage plan`'s table prints it: 1 decimal, 3 for scores in metres."""
    return f"{x:.3f} {unit}" if unit in ("m", "-m") else f"{x:.1f} {unit}"


def legend_below(fig, ax, handles, ncol=2):
    """The legend in a band under the plot, clear of its views and its axis labels."""
    legend = fig.legend(handles=handles, fontsize=7, loc="lower center", ncol=ncol,
                        frameon=False)
    fig.canvas.draw()
    height = legend.get_window_extent().height / fig.bbox.height
    fig.tight_layout(rect=(0, height + 0.01, 1, 1))
    return legend


def arrow_length(ax):
    """Arrows a fixed share of the drawing's size, so a building's views are not dots."""
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    return 0.06 * max(x1 - x0, y1 - y0)


def plot_plan(run_dir, plan):
    fig = plan_figure(run_dir, plan)
    fig.savefig(os.path.join(run_dir, "map.png"), dpi=120)
    plt.close(fig)


def plan_figure(run_dir, plan):
    """The plan's map.png: the map from above, the candidates coloured by what the method ranks
    them by (so the chosen view is the best-coloured one but for random and yamauchi), and the
    chosen view drawn last, larger, and named."""
    fig, ax = plt.subplots(figsize=(9.0, 7.4))
    handles = draw_top_view(ax, os.path.join(run_dir, "map_top.csv"), fig, occupied_by_height=False)
    method = plan["method"]
    key, unit, what = ranking_of(plan, method)
    best = plan["next_best_view"]
    # Best drawn last (on top); the chosen view after all of them.
    candidates = sorted(plan["candidates"], key=lambda c: c[key])
    values = [c[key] for c in candidates]
    norm = Normalize(vmin=min(values), vmax=max(max(values), min(values) + 1e-9))
    cmap = plt.get_cmap("viridis")
    xs = [c["sensor"]["position"][0] for c in candidates]
    ys = [c["sensor"]["position"][1] for c in candidates]
    for p in (best["sensor"]["position"], (plan.get("robot") or {}).get("sensor", {}).get(
            "position")):
        if p:
            xs.append(p[0])
            ys.append(p[1])
    ax.update_datalim(list(zip(xs, ys)))
    ax.set_aspect("equal")
    ax.autoscale()
    ax.margins(0.08)
    length = arrow_length(ax)
    # Many candidates (a building's frontiers) are drawn shorter, so that they do not cover the
    # map; the chosen view keeps its size.
    short = length * min(1.0, max(0.3, math.sqrt(30 / len(candidates))))
    yaws = [math.radians(c["yaw"]) for c in candidates]
    arrows = ax.quiver(xs[:len(candidates)], ys[:len(candidates)],
                       [math.cos(a) for a in yaws], [math.sin(a) for a in yaws], values,
                       cmap=cmap, norm=norm, angles="xy", scale_units="xy", scale=1 / short,
                       width=0.003, headwidth=4, headlength=4, headaxislength=3.5, zorder=3)
    fig.colorbar(arrows, ax=ax, shrink=0.6, pad=0.02, label=f"{what} [{unit}]")
    bx, by = best["sensor"]["position"][:2]
    yaw = math.radians(best["yaw"])
    ax.plot(bx, by, "o", ms=16, mfc="none", mec="#d50000", mew=2.5, zorder=5)
    ax.arrow(bx, by, 1.6 * length * math.cos(yaw), 1.6 * length * math.sin(yaw), color="#d50000",
             width=0.08 * length, head_width=0.3 * length, length_includes_head=True, zorder=6)
    # The label inside the plot, on the side of the view towards the middle.
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    ax.annotate(f"candidate {best['index']}\n{format_number(best[key], unit)}", (bx, by),
                xytext=(bx + (0.25 if bx < (x0 + x1) / 2 else -0.25) * (x1 - x0),
                        by + (0.15 if by < (y0 + y1) / 2 else -0.15) * (y1 - y0)),
                ha="center", va="center", fontsize=9, weight="bold", color="#d50000", zorder=7,
                arrowprops={"arrowstyle": "-", "color": "#d50000", "lw": 1},
                bbox={"boxstyle": "round", "fc": "white", "ec": "#d50000", "alpha": 0.85})
    handles += [plt.Line2D([], [], marker=r"$\rightarrow$", ls="", ms=10, color=cmap(0.5),
                           label=f"{len(candidates)} candidate views (colour: {what})"),
                plt.Line2D([], [], marker=r"$\rightarrow$", ls="", ms=14, color="#d50000",
                           label=f"next best view: candidate {best['index']}")]
    if plan.get("robot"):
        rx, ry = plan["robot"]["sensor"]["position"][:2]
        ax.plot(rx, ry, "s", color="black", ms=8, zorder=6)
        handles.append(plt.Line2D([], [], marker="s", ls="", color="black",
                                  label=f"robot ({plan['robot']['from']})"))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    label = method + (f", a = {plan['alpha']}" if method in OBSERVABILITY_METHODS else "")
    title = f"next best view ({label}): candidate {best['index']}\n{what}: " + \
        format_number(best[key], unit)
    if method in OBSERVABILITY_METHODS:
        other = ("predicted_gain", plan["units"].get("predicted_gain", "bits")) \
            if unit == "cells" else ("predicted_cells", "cells")
        # NOTE: `vantage plan --no-prediction` leaves the chosen view's bits null.
        if best.get(other[0]) is not None:
            title += f" ({format_number(best[other[0]], other[1])})"
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.2)
    legend_below(fig, ax, handles)
    return fig


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: plot_run.py RUN_DIR")
    run_dir = argv[1]
    if os.path.exists(os.path.join(run_dir, "plan.json")):
        with open(os.path.join(run_dir, "plan.json")) as f:
            plot_plan(run_dir, json.load(f))
        return
    if not os.path.exists(os.path.join(run_dir, "run.json")):
        sys.exit(f"plot_run.py: {run_dir} holds neither run.json (vantage explore) nor plan.json "
                 "(vantage plan)")
    with open(os.path.join(run_dir, "run.json")) as f:
        run = json.load(f)
    scans = read_csv(os.path.join(run_dir, "scans.csv"))
    plot_progress(run_dir, scans, run)
    if run["scene"].get("kind") == "office":
        plot_office_map(run_dir, run)
    else:
        plot_map(run_dir, run)


if __name__ == "__main__":
    main(sys.argv)
