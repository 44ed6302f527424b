"""Every method's choices judged by the truth (scripts/views_by_truth.py) on hand-made hit sets:
the true coverage curve of a trial's views worked out by hand, and the greedy oracle's order on
the same hit sets, which can need more scans to a level than another order."""

import sys

import pytest

from test_set_cover import write_truth


@pytest.fixture
def views_by_truth(source_dir):
    sys.path.insert(0, str(source_dir / "scripts"))
    import views_by_truth
    yield views_by_truth
    sys.path.remove(str(source_dir / "scripts"))


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
        if len(cells) == 8 and cells[1].isdigit():
            rows[cells[0]] = cells[1:]
        if len(cells) == 4 and cells[1].startswith("0."):
            curves[cells[0]] = cells[1:]
    assert rows["truth-greedy"] == ["1", "1.375", "-", "3.00", "4.00", "4.00", "0 of 3"]
    assert rows["cover"] == ["1", "1.375", "-", "3.00", "3.00", "3.00", "2 of 3"]
    # The curves after scans 1, 2, 3: the oracle's 1/8, 5/8, 7/8; the trial's 1/8, 4/8, 8/8.
    assert curves["truth-greedy"] == ["0.125", "0.625", "0.875"]
    assert curves["cover"] == ["0.125", "0.500", "1.000"]


def test_no_scans_csv_is_an_error(tmp_path, views_by_truth):
    with pytest.raises(SystemExit, match="no .*scans.csv"):
        views_by_truth.main(["views_by_truth.py", str(tmp_path)])
