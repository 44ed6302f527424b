"""The pictures the plot scripts draw (scripts/plot_run.py, plot_ray.py), checked on the figures
they build: what the candidates are coloured and titled by, where the legend sits, the ticks."""

import csv
import json
import math
import pathlib

import matplotlib
import pytest

matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from conftest import tree_modules


@pytest.fixture(scope="module")
def scripts(source_dir):
    with tree_modules(source_dir / "scripts", "plot_run", "plot_ray") as modules:
        yield modules


@pytest.fixture
def saved(monkeypatch):
    """The figures the scripts save, by file name: the scripts are run as `vantage` runs them
    (their main) and their figures checked before they are closed."""
    figures = {}
    real = matplotlib.figure.Figure.savefig

    def savefig(fig, path, *args, **kwargs):
        figures[pathlib.Path(path).name] = fig
        fig.canvas.draw()
        return real(fig, path, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", savefig)
    monkeypatch.setattr(plt, "close", lambda *args: None)
    yield figures
    for fig in figures.values():
        matplotlib.pyplot.close(fig)
    

def write_top(folder, n=20, res=0.1, ny=None):
    """A map_top.csv of an n x ny x 4 grid (ny = n unless given) with an occupied block."""
    ny = n if ny is None else ny
    rows = [f"# grid origin 0 0 0 resolution {res} dims {n} {ny} 4", "x,y,occupied,unobserved,top"]
    for j in range(ny):
        for i in range(n):
            occupied = 8 <= i < 12 and 8 <= j < 12
            rows.append(f"{(i + 0.5) * res},{(j + 0.5) * res},{int(occupied)},"
                        f"{0 if occupied else 2},{0.25 if occupied else ''}")
    (folder / "map_top.csv").write_text("\n".join(rows) + "\n")


def candidate(index, angle, bits, cells):
    x, y = 1.0 + 0.8 * math.cos(angle), 1.0 + 0.8 * math.sin(angle)
    yaw = math.degrees(angle + math.pi)
    return {"index": index, "sensor": {"position": [x, y, 0.5],
                                       "quaternion_xyzw": [0, 0, 0, 1]},
            "yaw": yaw, "predicted_gain": bits, "predicted_cells": cells, "greedy_gain": cells,
            "score": cells}


def survival_plan(units_score="cells"):
    """A survival plan whose ranking (cells) disagrees with its bits: the chosen view, 2, has the
    most cells and the fewest bits. units_score "bits" is what plan.json said before the fix."""
    gains = [(0, 900.0, 100.0), (1, 800.0, 200.0), (2, 100.0, 5000.0), (3, 700.0, 300.0)]
    candidates = [candidate(i, 2 * math.pi * i / 4, bits, cells) for i, bits, cells in gains]
    ranked = [candidates[2], candidates[3], candidates[1], candidates[0]]
    return {"method": "survival", "alpha": 0.995, "objective": "cells",
            "units": {"predicted_gain": "bits", "predicted_cells": "cells", "greedy_gain": "cells",
                      "score": units_score, "travel": "m"},
            "next_best_view": candidates[2], "candidates": ranked, "robot": None}


@pytest.mark.parametrize("units_score", ["cells", "bits"])
def test_plan_map_ranks_by_the_methods_score_in_its_unit(scripts, tmp_path, saved, units_score):
    plot_run, _ = scripts
    fig = plan_map(plot_run, saved, tmp_path, survival_plan(units_score))
    ax = fig.axes[0]
    # The chosen view's number and unit in the title: its cells, the ranking's, then its bits.
    assert "5000.0 cells" in ax.get_title(), ax.get_title()
    assert "(100.0 bits)" in ax.get_title(), ax.get_title()
    # The candidates are coloured by their cells, the chosen one the best-coloured.
    arrows = [c for c in ax.collections if isinstance(c, matplotlib.quiver.Quiver)]
    assert len(arrows) == 1
    values = list(arrows[0].get_array())
    assert sorted(values) == [100.0, 200.0, 300.0, 5000.0]
    assert max(values) == 5000.0
    bar = [a for a in fig.axes if "[cells]" in a.get_ylabel()]
    assert bar, [a.get_ylabel() for a in fig.axes]
    assert "cells seen" in bar[0].get_ylabel()
    # The chosen view is named on the map, beside its number.
    texts = [t.get_text() for t in ax.texts]
    assert any("candidate 2" in t and "5000.0 cells" in t for t in texts), texts


def test_plan_map_of_the_paper_method_ranks_by_bits(scripts, tmp_path, saved):
    plot_run, _ = scripts
    plan = survival_plan()
    plan["method"], plan["objective"], plan["units"]["score"] = "probabilistic", "bits", "bits"
    for c in plan["candidates"]:
        c["score"] = c["predicted_gain"]
    plan["next_best_view"] = plan["candidates"][-1]  # candidate 0: 900 bits
    fig = plan_map(plot_run, saved, tmp_path, plan)
    ax = fig.axes[0]
    assert "900.0 bits" in ax.get_title() and "(100.0 cells)" in ax.get_title(), ax.get_title()
    arrows = [c for c in ax.collections if isinstance(c, matplotlib.quiver.Quiver)][0]
    assert max(arrows.get_array()) == 900.0


def plan_map(plot_run, saved, folder, plan, **grid):
    """map.png's figure as `vantage plan` has plot_run.py draw it."""
    write_top(folder, **grid)
    (folder / "plan.json").write_text(json.dumps(plan))
    plot_run.main(["plot_run.py", str(folder)])
    return saved["map.png"]


def overlaps(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_plan_map_legend_covers_neither_the_views_nor_the_axis_label(scripts, tmp_path, saved):
    plot_run, _ = scripts
    # A wide map (a corridor) leaves a short plot, where a legend placed by the plot's height
    # slid over the axis label.
    fig = plan_map(plot_run, saved, tmp_path, survival_plan(), n=120, ny=20)
    assert_legend_clear(fig)


def assert_legend_clear(fig):
    """The legend overlaps neither the map (its views) nor the axis labels, nor do the map's
    texts (the chosen view's label) cover the labels."""
    fig.canvas.draw()  # the labels' places as saved (their first draw leaves them stale)
    ax = fig.axes[0]
    renderer = fig.canvas.get_renderer()
    legend = fig.legends[0] if fig.legends else ax.get_legend()
    box = legend.get_window_extent(renderer)
    labels = [ax.xaxis.label.get_window_extent(renderer),
              ax.yaxis.label.get_window_extent(renderer)]
    assert not any(overlaps(box, label) for label in labels)
    assert not overlaps(box, ax.get_window_extent(renderer))  # nothing drawn under it
    for text in ax.texts:
        assert not any(overlaps(text.get_window_extent(renderer), label) for label in labels), \
            text.get_text()


def test_explore_map_legend_covers_no_view(scripts, tmp_path, saved):
    plot_run, _ = scripts
    write_progress_run(tmp_path)
    plot_run.main(["plot_run.py", str(tmp_path)])
    assert_legend_clear(saved["map.png"])


def write_progress_run(folder):
    """An explore folder of 2 scans from one place on a table top's ring."""
    scans = [{"scan": "1", "unobserved": "900", "coverage": "0.4"},
             {"scan": "2", "unobserved": "500", "coverage": "0.7"}]
    pose = {"position": [1.0, 0.2, 0.5], "quaternion_xyzw": [0, 0, 0, 1]}
    run = {"scene": {"name": "t", "kind": "tabletop",
                     "grid": {"origin": [0, 0, 0], "resolution": 0.1, "dims": [20, 20, 4]}},
           "config": {"method": "greedy"}, "candidates": [pose],
           "scans": [{"scan": 1, "pose": pose}, {"scan": 2, "pose": pose}]}
    write_top(folder)
    (folder / "run.json").write_text(json.dumps(run))
    with open(folder / "scans.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(scans[0]))
        w.writeheader()
        w.writerows(scans)


def test_progress_ticks_whole_scans(scripts, tmp_path, saved):
    plot_run, _ = scripts
    write_progress_run(tmp_path)
    plot_run.main(["plot_run.py", str(tmp_path)])
    fig = saved["unobserved.png"]
    ticks = [t for t in fig.axes[0].get_xticks() if 1 <= t <= 2]
    assert ticks and all(float(t).is_integer() for t in ticks), ticks


def test_ray_gains_have_their_own_axis_in_bits(scripts, tmp_path, saved):
    _, plot_ray = scripts
    table = tmp_path / "ray.csv"
    with open(table, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["cell", "occupancy", "visibility", "posterior", "gain"])
        for cell, gain in enumerate([0.5, 2.0, -1.5, 0.1]):
            w.writerow([cell, 0.5, 0.9, 0.5, gain])
    plot_ray.main(["plot_ray.py", str(table), str(tmp_path / "ray.png")])
    fig = saved["ray.png"]
    (bits,) = [a for a in fig.axes if "bits" in a.get_ylabel()]
    low, high = bits.get_ylim()
    assert low < -1.5 and high > 2.0
    probability = [a for a in fig.axes if a.get_ylabel() == "probability"][0]
    assert all(line.get_label() != "gain [bits]" for line in probability.get_lines())
