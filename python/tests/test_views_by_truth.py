"""Every method's choices judged by the truth (scripts/views_by_truth.py) on hand-made hit sets:
the true coverage curve of a trial's views worked out by hand, the greedy oracle's order on the
same hit sets, which can need more scans to a level than another order, and that oracle priced
by travel, which takes a nearer view first where the price of motion says so."""

import pytest

from conftest import tree_modules
from test_set_cover import write_truth


@pytest.fixture
def views_by_truth(source_dir):
    with tree_modules(source_dir / "scripts", "views_by_truth") as (module,):
        yield module


def test_a_better_order_than_the_greedy_oracles_is_found_out(tmp_path, views_by_truth, capsys):
    # V = cells 0..7; the start hits 7. The greedy oracle takes view 0 (4 new cells, nearer than
    # view 2), then view 2, then view 1: coverage 1/8, 5/8, 7/8 over the 3 scans of the run. The
    # trial's views 1 then 2 give 1/8, 4/8, 8/8: 90 % and 95 % at scan 3, where the oracle's order
    # never reaches them within 3 scans (counted 4). Areas above both curves: 1.375 scans.
    views = [{0, 1, 2, 3}, {0, 1, 4}, {2, 3, 5, 6}]
    write_truth(tmp_path, "toy", views, [{7}], positions=[1.0, 5.0, 2.0], start_positions=[0.0])
    (tmp_path / "scans.csv").write_text(
        "scene,method,alpha,objective,trial,scan,view\n"
        "toy,cover,,,0,1,-1\ntoy,cover,,,0,2,1\ntoy,cover,,,0,3,2\n")
    views_by_truth.main(["views_by_truth.py", str(tmp_path)])
    rows, curves = {}, {}
    for line in capsys.readouterr().out.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 9 and cells[1].isdigit():
            rows[cells[0]] = cells[1:]
        if len(cells) == 4 and cells[1].startswith("0."):
            curves[cells[0]] = cells[1:]
    # Travel over the run's 3 scans: the oracle's views 0 and 2 (1 m, then 1 m), the trial's 1 and
    # 2 (5 m, then 3 m). Priced at 0.5 /m the oracle takes the same views: view 0's 4 new cells at
    # e^-0.5 outweigh view 2's 4 at e^-1.
    assert rows["truth-greedy"] == ["1", "1.375", "-", "3.00", "4.00", "4.00", "2.00", "0 of 3"]
    assert rows["truth-latombe"] == rows["truth-greedy"]
    assert rows["cover"] == ["1", "1.375", "-", "3.00", "3.00", "3.00", "8.00", "2 of 3"]
    # The curves after scans 1, 2, 3: the oracle's 1/8, 5/8, 7/8; the trial's 1/8, 4/8, 8/8.
    assert curves["truth-greedy"] == ["0.125", "0.625", "0.875"]
    assert curves["cover"] == ["0.125", "0.500", "1.000"]


def read_rows(text):
    rows = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 9 and cells[1].isdigit():
            rows[cells[0]] = cells[1:]
    return rows


def test_the_oracle_priced_by_travel_takes_the_near_view_first(tmp_path, views_by_truth, capsys):
    # V = cells 0..5; the start (at 0 m) hits 5. View 0 (at 10 m) adds 3 cells, view 1 (at 1 m) 2.
    # The greedy oracle takes view 0 then view 1: 1/6, 4/6, 6/6, 10 + 9 m. Priced at 0.5 /m, view
    # 0 is worth 3 e^-5 = 0.02 and view 1 2 e^-0.5 = 1.21: view 1 first, 1/6, 3/6, 6/6, 1 + 9 m.
    # At --lambda 0 it is the greedy oracle again.
    write_truth(tmp_path, "toy", [{0, 1, 2}, {3, 4}], [{5}], positions=[10.0, 1.0],
                start_positions=[0.0])
    (tmp_path / "scans.csv").write_text(
        "scene,method,alpha,objective,trial,scan,view\n"
        "toy,near,,,0,1,-1\ntoy,near,,,0,2,1\ntoy,near,,,0,3,0\n")
    views_by_truth.main(["views_by_truth.py", str(tmp_path)])
    rows = read_rows(capsys.readouterr().out)
    # Areas above the curves: 5/6 + 2/6 + 0 = 1.167 scans, and 5/6 + 3/6 = 1.333 scans.
    assert rows["truth-greedy"] == ["1", "1.167", "-", "3.00", "3.00", "3.00", "19.00", "0 of 3"]
    assert rows["truth-latombe"] == ["1", "1.333", "-", "3.00", "3.00", "3.00", "10.00", "0 of 3"]
    assert rows["near"] == rows["truth-latombe"]
    views_by_truth.main(["views_by_truth.py", str(tmp_path), "--lambda", "0"])
    rows = read_rows(capsys.readouterr().out)
    assert rows["truth-latombe"] == rows["truth-greedy"]


def test_a_bad_lambda_is_a_command_line_error(tmp_path, views_by_truth):
    with pytest.raises(SystemExit) as exit_info:
        views_by_truth.main(["views_by_truth.py", str(tmp_path), "--lambda", "-1"])
    assert exit_info.value.code == 2


def test_no_scans_csv_is_an_error(tmp_path, views_by_truth):
    with pytest.raises(SystemExit, match="no .*scans.csv"):
        views_by_truth.main(["views_by_truth.py", str(tmp_path)])
