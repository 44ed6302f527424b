"""The sweep summary's per-trial metrics and paired comparison with greedy (scripts/plot_bench.py),
on a small synthetic scans.csv whose answers are worked out by hand: AUC, scans and travel to
90 % and 95 % coverage, a censored trial, the Wilcoxon signed-rank p-values."""

import csv

import pytest

HEADER = ("scene,method,alpha,trial,scan,view,predicted_gain,greedy_predicted_gain,actual_gain,"
          "unobserved,coverage,plan_seconds,travel_m,fallback,predicted_cells,alpha_used,objective,"
          "pose_error_before_m,pose_error_after_m,pose_error_final_m,register_seconds,"
          "segment_seconds,integrate_seconds,reference_seconds,displacement_before_m,"
          "displacement_after_m,displacement_final_m")

# Per scan 1..4: unobserved cells, coverage, travel [m].
GREEDY = ([1000, 400, 200, 100], [0.5, 0.85, 0.92, 0.96], [0, 2, 2, 2])


def latombe(i, censored):
    """AUC = 1375 + 10 i (greedy's: 1150); 90 % at scan 4 (greedy: 3); 95 % at scan 4 unless
    censored; half greedy's travel."""
    return ([1000, 500 + 10 * i, 300, 150], [0.5, 0.8, 0.88, 0.93 if censored else 0.95],
            [0, 1, 1, 1])


def rows(scene, method, trial, curve):
    unobserved, coverage, travel = curve
    out = []
    for k in range(4):
        fields = {name: "0" for name in HEADER.split(",")}
        fields.update(scene=scene, method=method, alpha="", objective="", trial=str(trial),
                      scan=str(k + 1), view=str(k), predicted_gain="", greedy_predicted_gain="",
                      predicted_cells="", alpha_used="", unobserved=str(unobserved[k]),
                      coverage=str(coverage[k]), travel_m=str(travel[k]))
        out.append(",".join(fields[name] for name in HEADER.split(",")))
    return out


@pytest.fixture
def sweep(tmp_path, plot_bench):
    lines = [HEADER]
    i = 0
    for scene in ("pile-12-s0001", "pile-12-s0002"):
        for trial in range(3):
            lines += rows(scene, "greedy", trial, GREEDY)
            lines += rows(scene, "random", trial, GREEDY)  # the same as greedy: no difference
            lines += rows(scene, "latombe", trial, latombe(i, scene.endswith("2") and trial == 2))
            i += 1
    (tmp_path / "scans.csv").write_text("\n".join(lines) + "\n")
    plot_bench.main(["plot_bench.py", str(tmp_path)])
    return tmp_path


def table(summary, method, measure):
    """The paired table's cells for one method and measure."""
    for line in summary.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 7 and cells[0] == method and cells[1] == measure:
            return dict(zip(["method", "measure", "pairs", "median", "ratio", "p", "censored"],
                            cells))
    raise AssertionError(f"no row for {method}, {measure} in:\n{summary}")


def test_trials_csv_holds_each_trials_metrics(sweep):
    with open(sweep / "trials.csv", newline="") as f:
        trials = list(csv.DictReader(f))
    assert len(trials) == 18
    greedy = [t for t in trials if t["method"] == "greedy"]
    assert {t["auc_cells_scans"] for t in greedy} == {"1150"}
    assert {t["scans_to_90"] for t in greedy} == {"3"}
    assert {t["travel_to_90_m"] for t in greedy} == {"4"}
    assert {t["travel_m"] for t in greedy} == {"6"}
    late = {(t["scene"], t["trial"]): t for t in trials if t["method"] == "latombe"}
    assert late[("pile-12-s0001", "0")]["auc_cells_scans"] == "1375"
    assert late[("pile-12-s0002", "2")]["auc_cells_scans"] == "1425"
    # Censored: the level is never reached within the trial's scans.
    assert late[("pile-12-s0002", "2")]["scans_to_95"] == ""
    assert late[("pile-12-s0002", "2")]["travel_to_95_m"] == ""
    assert late[("pile-12-s0002", "1")]["scans_to_95"] == "4"


def test_paired_differences_from_greedy(sweep):
    summary = (sweep / "summary.md").read_text()
    auc = table(summary, "latombe", "AUC [cells x scans]")
    # Differences 225, 235, ..., 275 over 6 pairs, all positive: median 250, the exact two-sided
    # p-value 2 / 2^6.
    assert auc["pairs"] == "6"
    assert auc["median"] == "250"
    assert auc["ratio"] == f"{1400 / 1150:.3f}"
    assert auc["p"] == "0.031"
    travel = table(summary, "latombe", "travel [m]")
    assert (travel["median"], travel["ratio"]) == ("-3.00", "0.500")
    # The censored trial counts as the budget (4 scans) + 1; one nonzero difference.
    s95 = table(summary, "latombe", "scans to 95%")
    assert (s95["pairs"], s95["median"], s95["p"], s95["censored"]) == ("6", "0.0", "1", "1 / 0")
    assert table(summary, "latombe", "scans to 90%")["median"] == "1.0"
    # ... and its pair is left out of the travel to 95 %.
    t95 = table(summary, "latombe", "travel to 95% [m]")
    assert (t95["pairs"], t95["median"]) == ("5", "-3.00")


def test_all_zero_differences_give_p_one(sweep):
    summary = (sweep / "summary.md").read_text()
    for measure in ("AUC [cells x scans]", "travel [m]", "scans to 90%", "travel to 95% [m]"):
        row = table(summary, "random", measure)
        assert row["p"] == "1", (measure, row)
        assert float(row["median"]) == 0.0
        assert row["ratio"] == "1.000"


def test_wilcoxon_matches_scipy(plot_bench):
    from scipy.stats import wilcoxon
    d = [3.0, -1.0, 4.0, 1.5, 5.0, 9.0, -2.5, 6.0]
    assert plot_bench.wilcoxon_p(d) == pytest.approx(wilcoxon(d).pvalue)
    assert plot_bench.wilcoxon_p([0.0, 0.0]) == 1.0
    assert plot_bench.wilcoxon_p([]) is None


def test_levels_are_chosen_on_the_command_line(sweep, plot_bench):
    """--levels 85,92 records those levels instead: greedy reaches 85 % at scan 2 and 92 % at
    scan 3, latombe 85 % at scan 3."""
    try:
        plot_bench.main(["plot_bench.py", str(sweep), "--levels", "85,92"])
        with open(sweep / "trials.csv", newline="") as f:
            trials = list(csv.DictReader(f))
        assert "scans_to_90" not in trials[0]
        greedy = [t for t in trials if t["method"] == "greedy"]
        assert {t["scans_to_85"] for t in greedy} == {"2"}
        assert {t["scans_to_92"] for t in greedy} == {"3"}
        assert {t["scans_to_85"] for t in trials if t["method"] == "latombe"} == {"3"}
        with pytest.raises(SystemExit):
            plot_bench.main(["plot_bench.py", str(sweep), "--levels", "0,90"])
    finally:
        plot_bench.LEVELS = (0.90, 0.95)


def test_a_panel_with_nothing_to_draw_says_so_without_a_warning(tmp_path, plot_bench, caplog):
    # Greedy and random predict no cells seen, so the prediction-error panels have no line: each
    # says so, and matplotlib logs no warning of an empty legend.
    lines = [HEADER]
    for trial in range(2):
        lines += rows("pile-12-s0001", "greedy", trial, GREEDY)
        lines += rows("pile-12-s0001", "random", trial, GREEDY)
    (tmp_path / "scans.csv").write_text("\n".join(lines) + "\n")
    with caplog.at_level("WARNING"):
        plot_bench.main(["plot_bench.py", str(tmp_path)])
    assert not [r.getMessage() for r in caplog.records if "legend" in r.getMessage()]
    assert (tmp_path / "prediction_error.png").stat().st_size > 0
