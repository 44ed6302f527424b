"""scripts/price_of_motion.py on two synthetic sweeps of one lambda each, whose answers are worked
out by hand: a travel-ranked method is a point per lambda, greedy a reference point once, the
ratios to greedy pooled over the same trials, and the Pareto front."""

import sys

import pytest

from test_surface_summary import HEADER

# Per method and lambda: surface coverage after scans 1..3 and the travel of each scan [m].
# Areas above the curves: greedy 0.5 + 0.3 + 0.2 = 1.0; latombe+surface at lambda 0.5 0.9 and at
# 2 1.2 [scans]; travel greedy 4, latombe+surface 2 and 1 [m].
CURVES = {("greedy", 0.5): ([0.5, 0.7, 0.8], [0, 2, 2]),
          ("latombe+surface", 0.5): ([0.5, 0.75, 0.85], [0, 1, 1]),
          ("latombe+surface", 2.0): ([0.5, 0.6, 0.7], [0, 0.5, 0.5])}


def write_sweep(folder, lam):
    lines = [HEADER]
    for (method, at), (coverage, travel) in CURVES.items():
        if at != lam:
            continue
        for scene in ("tabletop-1", "pile-12-s0001"):
            for k in range(3):
                fields = {name: "0" for name in HEADER.split(",")}
                fields.update(scene=scene, method=method, alpha="", objective="", trial="0",
                              scan=str(k + 1), view=str(k), predicted_gain="",
                              greedy_predicted_gain="", predicted_cells="", alpha_used="",
                              travel_m=str(travel[k]), surface_coverage=str(coverage[k]),
                              raw_surface_coverage=str(coverage[k]))
                lines.append(",".join(fields[name] for name in HEADER.split(",")))
    folder.mkdir()
    (folder / "scans.csv").write_text("\n".join(lines) + "\n")
    (folder / "sweep.json").write_text(f'{{"lambda": {lam}, "candidates": "hemisphere"}}')


@pytest.fixture
def price_of_motion(plot_bench, source_dir):
    import price_of_motion
    yield price_of_motion
    sys.modules.pop("price_of_motion", None)


def test_a_point_per_lambda_ratios_to_greedy_and_the_front(tmp_path, price_of_motion, capsys):
    write_sweep(tmp_path / "half", 0.5)
    write_sweep(tmp_path / "two", 2.0)
    out = tmp_path / "price.png"
    price_of_motion.main(["price_of_motion.py", str(tmp_path / "half"), str(tmp_path / "two"),
                          "--out", str(out)])
    printed = capsys.readouterr().out
    rows = {}
    for line in printed.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 7 and cells[2].isdigit():
            rows[(cells[0], cells[1])] = cells[2:]
    assert rows[("greedy", "-")] == ["2", "1.000", "1.000", "4.00", "1.000"]
    assert rows[("latombe+surface", "0.5")] == ["2", "0.900", "0.900", "2.00", "0.500"]
    # NOTE: greedy ran in the lambda-0.5 sweep only, on the same scenes and starts.
    assert rows[("latombe+surface", "2")] == ["2", "1.200", "1.200", "1.00", "0.250"]
    # Area under the curves: greedy 2.0, lambda 0.5 2.1, lambda 2 1.8 [scans]: lambda 0.5 beats
    # greedy in both, lambda 2 travels least.
    assert printed.strip().endswith(
        "Pareto front (less travel, more area): latombe+surface λ=2, latombe+surface λ=0.5")
    assert out.stat().st_size > 0


def test_no_output_file_is_a_usage_error(tmp_path, price_of_motion):
    with pytest.raises(SystemExit, match="usage"):
        price_of_motion.main(["price_of_motion.py", str(tmp_path)])
