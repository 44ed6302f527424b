"""The sweep summary's surface-coverage part (scripts/plot_bench.py, docs/yardstick.md) on a small
synthetic scans.csv whose answers are worked out by hand: scans and travel to 80/90/95 % of the
visible surface (censored where not reached), the area above the coverage curve, the share of the
gap between greedy and the greedy oracle closed, the paired test, the Pareto front, and the
set-cover table."""


import pytest

HEADER = ("scene,method,alpha,trial,scan,view,predicted_gain,greedy_predicted_gain,actual_gain,"
          "unobserved,coverage,plan_seconds,travel_m,fallback,predicted_cells,alpha_used,objective,"
          "pose_error_before_m,pose_error_after_m,pose_error_final_m,register_seconds,"
          "segment_seconds,integrate_seconds,reference_seconds,displacement_before_m,"
          "displacement_after_m,displacement_final_m,surface_coverage,raw_surface_coverage")

# Per scan 1..4: surface coverage and travel [m]. Areas above the curves: greedy 1.05, the oracle
# 0.84, latombe 0.98 [scans]: latombe closes (1.05 - 0.98) / (1.05 - 0.84) = 1/3 of the gap.
CURVES = {"greedy": ([0.5, 0.7, 0.85, 0.9], [0, 2, 2, 2]),
          "greedy-oracle": ([0.5, 0.8, 0.9, 0.96], [0, 1, 1, 1]),
          "latombe": ([0.5, 0.75, 0.85, 0.92], [0, 1, 1, 1])}


def rows(scene, method, trial):
    coverage, travel = CURVES[method]
    out = []
    for k in range(4):
        fields = {name: "0" for name in HEADER.split(",")}
        fields.update(scene=scene, method=method, alpha="", objective="", trial=str(trial),
                      scan=str(k + 1), view=str(k), predicted_gain="", greedy_predicted_gain="",
                      predicted_cells="", alpha_used="", unobserved=str(1000 - 100 * k),
                      coverage="0.5", travel_m=str(travel[k]), surface_coverage=str(coverage[k]),
                      raw_surface_coverage=str(coverage[k] / 2))
        out.append(",".join(fields[name] for name in HEADER.split(",")))
    return out


@pytest.fixture
def sweep(tmp_path, plot_bench):
    lines = [HEADER]
    for scene in ("tabletop-1", "tabletop-2"):
        for trial in range(3):
            for method in CURVES:
                lines += rows(scene, method, trial)
    (tmp_path / "scans.csv").write_text("\n".join(lines) + "\n")
    (tmp_path / "sweep.json").write_text('{"candidates": "hemisphere"}')
    (tmp_path / "set_cover.csv").write_text(
        "scene,candidates,start,level,visible_cells,start_cells,greedy_views,set_cover_views,"
        "lower_bound,gap,status,seconds,tour_m,tour_method,greedy_tour_m,views\n"
        "tabletop-1,hemisphere,0,90,1000,300,7,6,6,0,optimal,1.5,2.25,exact,3.5,1 2 3 4 5 6\n")
    plot_bench.main(["plot_bench.py", str(tmp_path)])
    return tmp_path


def surface_row(summary, scene, method):
    part = summary.split(f"### {scene}")[1]
    for line in part.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if cells[0] == method:
            return cells
    raise AssertionError(f"no row for {method} in {scene}:\n{summary}")


def test_levels_areas_and_the_gap_closed_per_scene(sweep):
    summary = (sweep / "summary.md").read_text()
    greedy = surface_row(summary, "tabletop-1", "greedy")
    # method, trials, surface, raw, after 10 views, AAC, gap closed, scans to 80/90/95, travel
    # to 80/90/95; these trials took 4 scans, so none has a coverage after 10 views.
    assert greedy[1:7] == ["3", "90.0%", "45.0%", "-", "1.05", "0.00"]  # greedy closes none
    assert greedy[7:10] == ["3", "4", ">4 (3/3 cens.)"]
    assert greedy[10:13] == ["4.00", "6.00", "-"]
    oracle = surface_row(summary, "tabletop-1", "greedy-oracle")
    assert oracle[5:10] == ["0.84", "1.00", "2", "3", "4"]
    assert oracle[10:13] == ["1.00", "2.00", "3.00"]
    latombe = surface_row(summary, "tabletop-1", "latombe")
    assert latombe[5:10] == ["0.98", "0.33", "3", "4", ">4 (3/3 cens.)"]


def test_the_pooled_gap_and_the_paired_test(sweep):
    summary = (sweep / "summary.md").read_text()
    part = summary.split("### Gap closed between greedy and the greedy oracle")[1]
    rows = {}
    for line in part.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 6:
            rows[cells[0]] = cells
    # Six pairs, each 0.07 scans below greedy: the exact two-sided p is 2 / 2^6.
    assert rows["latombe"][1:] == ["6", "0.33", "0.33", "-0.07", "0.031"]
    assert rows["greedy-oracle"][1:] == ["6", "1.00", "1.00", "-0.21", "0.031"]


def test_the_set_cover_table_and_the_plot(sweep):
    summary = (sweep / "summary.md").read_text()
    assert "| tabletop-1 | 0 | 90% | 7 | 6 | 6 | 0 | optimal | 1.5 | 2.25 | 3.5 |" in summary
    assert (sweep / "coverage_travel.png").stat().st_size > 0


def test_the_pareto_front_keeps_what_nothing_beats_in_both(plot_bench):
    points = [(3.0, 3.16, "oracle"), (3.0, 3.02, "latombe"), (6.0, 2.95, "greedy"),
              (1.0, 2.0, "random"), (8.0, 3.5, "far")]
    assert [p[2] for p in plot_bench.pareto(points)] == ["random", "oracle", "far"]


def test_a_sweep_without_surface_columns_has_no_surface_part(tmp_path, plot_bench):
    old = HEADER.rsplit(",", 2)[0]
    lines = [old]
    for trial in range(2):
        for r in rows("tabletop-1", "greedy", trial):
            lines.append(r.rsplit(",", 2)[0])
    (tmp_path / "scans.csv").write_text("\n".join(lines) + "\n")
    plot_bench.main(["plot_bench.py", str(tmp_path)])
    assert "Surface coverage by scan points" not in (tmp_path / "summary.md").read_text()
    assert not (tmp_path / "coverage_travel.png").exists()


def test_the_pooled_table_gives_each_method_over_the_same_pairs_against_greedy(sweep):
    summary = (sweep / "summary.md").read_text()
    part = summary.split("### Every method over the same pairs, against greedy")[1]
    row = next([c.strip() for c in line.strip("|").split("|")] for line in part.splitlines()
               if line.startswith("| latombe |"))
    # AAC 0.98 [scans], 0.98 / 1.05 of greedy's, a third of the gap; 80 % at scan 3 as greedy,
    # 90 % at 4 as greedy, 95 % never (5); travel 3 m against greedy's 6; final 92 %.
    assert row[1:3] == ["0.980", "0.933"]
    assert row[4] == "0.33"
    assert [row[5], row[7], row[9]] == ["3.00", "4.00", "5.00"]
    assert row[11:13] == ["3.00", "0.500"]
    assert row[14] == "92.0%"


def test_the_oracle_against_greedy_case_by_case(sweep):
    # Scans to 80/90/95 %: greedy 3, 4 and never; the oracle 2, 3 and 4: never behind greedy.
    summary = (sweep / "summary.md").read_text()
    part = summary.split("### The greedy oracle against greedy, case by case")[1]
    assert "Cases (scene, start, level of 80%, 90%, 95%): 18." in part
    assert "more scans than greedy in 0 of them." in part
    assert "Never reached within 4 scans: greedy 6, the oracle 0 of the 18." in part


def test_an_oracle_behind_greedy_is_named(plot_bench):
    def trial(method, to80):
        m = {"scene": "pile-12-s0001", "trial": "1", "method": method}
        m.update({("scans_to", lv): None for lv in plot_bench.SURFACE_LEVELS})
        m[("scans_to", 0.80)] = to80
        return m
    lines = plot_bench.oracle_against_greedy([trial("greedy", 2), trial("greedy-oracle", 3)], 4)
    assert ("greedy in 1 of them: pile-12-s0001 start 1 to 80% (3 against 2).") in lines[2]
    assert lines[3] == "Never reached within 4 scans: greedy 2, the oracle 2 of the 3."
