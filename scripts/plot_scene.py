"""Top view of a Vantage scene: its solids, rooms, grid, start positions and candidate views.

Usage: plot_scene.py SCENE.json OUT.png

The JSON comes from `vantage scene NAME --json FILE` (every length in metres, yaw in radians).
"""

import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

COLOURS = {
    "floor": "#f2f2f2",
    "table": "#d9c3a5",
    "wall": "#555555",
    "desk": "#b08d57",
    "table_furniture": "#b08d57",
    "chair": "#7f6a93",
    "shelf": "#8c5a3c",
    "cabinet": "#6b7b8c",
    "box": "#e07b39",
    "cylinder": "#3c8dbc",
    "sphere": "#5cb85c",
    "mesh": "#c0392b",
}


def main(data_path, out_path):
    with open(data_path, encoding="utf-8") as f:
        scene = json.load(f)
    tabletop = scene["kind"] == "tabletop"
    (fx0, fy0), (fx1, fy1) = scene["floor"]
    grid = scene["grid"]

    # What to frame: the table top's ring of views, or the whole office floor.
    points = [(v["x"], v["y"]) for v in scene["candidates"] + scene["starts"]]
    xs = [p[0] for p in points] + [grid["min"][0], grid["max"][0]]
    ys = [p[1] for p in points] + [grid["min"][1], grid["max"][1]]
    if not tabletop:
        xs += [fx0, fx1]
        ys += [fy0, fy1]
    pad = 0.15 * max(max(xs) - min(xs), max(ys) - min(ys))
    x0, x1, y0, y1 = min(xs) - pad, max(xs) + pad, min(ys) - pad, max(ys) + pad
    width = 7.0
    height = max(4.0, width * (y1 - y0) / (x1 - x0))
    width += 2.5  # room for the legend beside the plot
    fig, ax = plt.subplots(figsize=(width, height))

    if not tabletop:
        ax.add_patch(Rectangle((fx0, fy0), fx1 - fx0, fy1 - fy0, color=COLOURS["floor"], zorder=0))
    # Draw low things first so that tall ones stay visible from above.
    shapes = sorted(
        (s for s in scene["shapes"] if s["kind"] != "floor"), key=lambda s: s["zmax"]
    )
    seen_kinds = set()
    for shape in shapes:
        kind = shape["kind"]
        if kind == "table" and not tabletop:
            kind = "table_furniture"
        colour = COLOURS.get(kind, "#999999")
        label = None
        if kind not in seen_kinds:
            seen_kinds.add(kind)
            label = {"table_furniture": "table", "mesh": "scanned model"}.get(kind, kind)
        if len(shape["outline"]) >= 3:
            ax.add_patch(
                Polygon(shape["outline"], closed=True, facecolor=colour, edgecolor="black",
                        linewidth=0.3, alpha=0.9, zorder=2, label=label)
            )
    for room in scene["rooms"]:
        (rx0, ry0), (rx1, ry1) = room["min"], room["max"]
        inset = 0.02 * max(x1 - x0, y1 - y0)
        ax.text(rx0 + inset, ry1 - inset, room["name"], ha="left", va="top", fontsize=7,
                color="#555555", zorder=3)

    gx0, gy0 = grid["min"][0], grid["min"][1]
    gx1, gy1 = grid["max"][0], grid["max"][1]
    ax.add_patch(
        Rectangle((gx0, gy0), gx1 - gx0, gy1 - gy0, fill=False, linestyle="--", linewidth=0.8,
                  edgecolor="#2c7fb8", zorder=3,
                  label="grid {} x {} x {} @ {:.4g} m".format(*grid["dims"], grid["resolution"]))
    )

    arrow = 0.08 * max(x1 - x0, y1 - y0)
    for i, v in enumerate(scene["candidates"]):
        ax.annotate("", xy=(v["x"] + arrow * math.cos(v["yaw"]), v["y"] + arrow * math.sin(v["yaw"])),
                    xytext=(v["x"], v["y"]),
                    arrowprops=dict(arrowstyle="->", color="#888888", linewidth=0.8), zorder=4)
    if scene["candidates"]:
        ax.plot([], [], color="#888888", label=f"{len(scene['candidates'])} candidate views")
    sx = [v["x"] for v in scene["starts"]]
    sy = [v["y"] for v in scene["starts"]]
    ax.scatter(sx, sy, s=90, facecolor="#1f5fbf", edgecolor="white", zorder=5,
               label=f"{len(scene['starts'])} start positions")
    for i, v in enumerate(scene["starts"]):
        ax.text(v["x"], v["y"], str(i), ha="center", va="center", fontsize=6, color="white",
                zorder=6)
        if not tabletop:
            ax.annotate("", xy=(v["x"] + arrow * math.cos(v["yaw"]), v["y"] + arrow * math.sin(v["yaw"])),
                        xytext=(v["x"], v["y"]),
                        arrowprops=dict(arrowstyle="->", color="#1f5fbf", linewidth=1.0), zorder=5)

    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    sensor = scene["sensor"]
    ax.set_title(f"{scene['name']}: top view ({sensor['name']}, "
                 f"{math.degrees(sensor['h_fov']):.0f}° wide, {sensor['max_range']:g} m range)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7, framealpha=0.9)
    fig.tight_layout()
    fig.savefig(out_path, dpi=130)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
