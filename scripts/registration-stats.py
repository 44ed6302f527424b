#!/usr/bin/python3
"""Registration figures over a set of `vantage explore` run folders (issue 14's bar).

    scripts/registration-stats.py RUN_DIR [RUN_DIR ...]     # folders holding run.json
    scripts/registration-stats.py /tmp/runs/*                # e.g. every run of an explore loop
    scripts/registration-stats.py SWEEP_DIR                  # a `vantage bench` folder: every
                                                             # trial's rows in scans.csv/trials/

Over every scan after each run's first (the first defines the map frame and is exact): the
translation error of the pose used after registration (median, 95th percentile, worst), the
worst worsening (after minus before; > 0 means registration moved the pose away from the truth),
how many scans got worse by more than 1 mm, and the median registration time per scan. "final"
is the pose the map holds at the end of the run: a scan that fell back and was registered again
after a later scan (MapperConfig::reregister_window) counts there at its second registration. Run
folders whose scene is an office are reported apart from table tops.
"""
import csv
import json
import math
import sys
from pathlib import Path


def percentile(values, q):
    """Linear interpolation between closest ranks (numpy's default)."""
    s = sorted(values)
    if not s:
        return math.nan
    k = (len(s) - 1) * q
    lo, hi = math.floor(k), math.ceil(k)
    return s[lo] + (s[hi] - s[lo]) * (k - lo)


SCANS_CSV_HEADER = (
    "scene,method,alpha,trial,scan,view,predicted_gain,greedy_predicted_gain,actual_gain,"
    "unobserved,coverage,plan_seconds,travel_m,fallback,predicted_cells,alpha_used,objective,"
    "pose_error_before_m,pose_error_after_m,pose_error_final_m,register_seconds,segment_seconds,"
    "integrate_seconds,reference_seconds").split(",")


def add_sweep(folder, groups):
    """Adds the rows of a `vantage bench` folder (its scans.csv, or its trials/*.csv), which keep
    the pose errors and registration times in their columns; False if it is no sweep folder."""
    files = [folder / "scans.csv"] if (folder / "scans.csv").is_file() else \
        sorted((folder / "trials").glob("*.csv")) if (folder / "trials").is_dir() else []
    if not files:
        return False
    rows = groups.setdefault(f"sweep {folder.name}", [])
    for f in files:
        with open(f, newline="") as handle:
            # NOTE: a trial's file is rows only, under scans.csv's header (README, vantage explore)
            first = handle.readline()
            handle.seek(0)
            names = None if first.startswith("scene,") else SCANS_CSV_HEADER
            for r in csv.DictReader(handle, fieldnames=names):
                if int(r["scan"]) < 2 or "pose_error_final_m" not in r:
                    continue
                rows.append((float(r["pose_error_before_m"]), float(r["pose_error_after_m"]),
                             float(r["register_seconds"]), float(r["pose_error_final_m"])))
    return True


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    groups = {}
    for arg in argv[1:]:
        if add_sweep(Path(arg), groups):
            continue
        path = Path(arg) / "run.json"
        if not path.is_file():
            sys.exit(f"registration-stats: {path}: no such file (expected a run or sweep folder)")
        try:
            run = json.loads(path.read_text())
            kind = run["scene"]["kind"]
            scans = run["scans"]
        except (json.JSONDecodeError, KeyError, TypeError) as e:
            sys.exit(f"registration-stats: {path}: not a run.json ({e})")
        rows = groups.setdefault(kind, [])
        for scan in scans[1:]:
            e = scan["pose_error"]
            rows.append((e["before_m"], e["after_m"], scan["seconds"]["register"],
                         e.get("final_m", e["after_m"])))
    for kind, rows in sorted(groups.items()):
        before = [r[0] for r in rows]
        after = [r[1] for r in rows]
        final = [r[3] for r in rows]
        worse = [max(a, f) - b for b, a, _, f in rows]
        seconds = [r[2] for r in rows]
        print(f"{kind}: {len(rows)} registered scans from {len(argv) - 1} runs")
        print(f"  pose error before  median {1e3 * percentile(before, 0.5):7.2f} mm"
              f"  p95 {1e3 * percentile(before, 0.95):7.2f} mm"
              f"  worst {1e3 * max(before):7.2f} mm")
        print(f"  pose error after   median {1e3 * percentile(after, 0.5):7.2f} mm"
              f"  p95 {1e3 * percentile(after, 0.95):7.2f} mm"
              f"  worst {1e3 * max(after):7.2f} mm")
        print(f"  pose error final   median {1e3 * percentile(final, 0.5):7.2f} mm"
              f"  p95 {1e3 * percentile(final, 0.95):7.2f} mm"
              f"  worst {1e3 * max(final):7.2f} mm"
              f"  ({sum(f < a - 1e-9 for _, a, _, f in rows)} scans registered again)")
        print(f"  worst worsening {1e3 * max(worse):+.2f} mm;"
              f" scans made worse by > 1 mm: {sum(w > 1e-3 for w in worse)}")
        print(f"  registration time  median {1e3 * percentile(seconds, 0.5):.1f} ms"
              f"  p95 {1e3 * percentile(seconds, 0.95):.1f} ms per scan")


if __name__ == "__main__":
    main(sys.argv)
