#!/usr/bin/python3
"""The map seen from above, as `map_top.csv` gives it (vantage/io/map_files.hpp): a module the
plot scripts share, not a script of its own.

Each (x, y) column of the grid with an occupied or an unobserved cell is one row: its centre,
how many cells of each class it holds, and the height of its highest occupied cell.
"""
import csv

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap

UNOBSERVED_CMAP = "RdPu"
OCCUPIED_COLOR = "#37474f"


def read_top_view(path):
    """Returns (grid, rows): grid = {origin, resolution, dims}, rows = list of dicts."""
    with open(path, newline="") as f:
        words = f.readline().split()
        if words[:3] != ["#", "grid", "origin"]:
            raise SystemExit(f"{path}: the first line is not '# grid origin ...'")
        grid = {"origin": [float(v) for v in words[3:6]], "resolution": float(words[7]),
                "dims": [int(v) for v in words[9:12]]}
        rows = list(csv.DictReader(f))
    return grid, rows


def draw_top_view(ax, path, fig, occupied_by_height=True):
    """Draws on `ax` the columns with unobserved cells (shaded by how many they hold) and the
    occupied ones (coloured by the height of their highest occupied cell, or flat), with the
    grid's outline and a colour bar on `fig` for each shading. Returns the legend handles of
    what it drew."""
    grid, rows = read_top_view(path)
    (ox, oy, _), res, (nx, ny, nz) = grid["origin"], grid["resolution"], grid["dims"]
    unobserved = np.zeros((ny, nx))
    top = np.full((ny, nx), np.nan)
    for r in rows:
        i = min(nx - 1, max(0, int((float(r["x"]) - ox) / res)))
        j = min(ny - 1, max(0, int((float(r["y"]) - oy) / res)))
        unobserved[j, i] = int(r["unobserved"])
        if r["top"]:
            top[j, i] = float(r["top"])
    extent = (ox, ox + nx * res, oy, oy + ny * res)
    shade = ax.imshow(np.ma.masked_equal(unobserved, 0), origin="lower", extent=extent,
                      interpolation="nearest", cmap=UNOBSERVED_CMAP, vmin=0,
                      vmax=max(1, unobserved.max()))
    fig.colorbar(shade, ax=ax, shrink=0.6, pad=0.02,
                 label=f"unobserved cells in the column (of {nz})")
    handles = [plt.Rectangle((0, 0), 1, 1, color=plt.get_cmap(UNOBSERVED_CMAP)(0.5),
                             label="unobserved (shade: cells in the column)")]
    occupied = np.ma.masked_invalid(top)
    if occupied_by_height and occupied.count():
        image = ax.imshow(occupied, origin="lower", extent=extent, interpolation="nearest",
                          cmap="viridis")
        fig.colorbar(image, ax=ax, shrink=0.6, pad=0.02,
                     label="height of the highest occupied cell [m]")
        handles.append(plt.Rectangle((0, 0), 1, 1, color=plt.get_cmap("viridis")(0.6),
                                     label="occupied (colour: height)"))
    elif occupied.count():
        ax.imshow((~np.ma.getmaskarray(occupied)).astype(int), origin="lower", extent=extent,
                  interpolation="nearest", cmap=one_color(OCCUPIED_COLOR), vmin=0, vmax=1)
        handles.append(plt.Rectangle((0, 0), 1, 1, color=OCCUPIED_COLOR, label="occupied"))
    ax.add_patch(plt.Rectangle((ox, oy), nx * res, ny * res, fill=False, ls=":", color="grey"))
    handles.append(plt.Line2D([], [], ls=":", color="grey", label="map's grid"))
    return handles


def one_color(color):
    """A colour map that draws 1 in `color` and 0 transparent."""
    return ListedColormap([(1, 1, 1, 0), color])
