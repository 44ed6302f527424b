#!/usr/bin/python3
"""Registration figures over a set of `vantage explore` run folders (issue 14's bar).

    scripts/registration-stats.py RUN_DIR [RUN_DIR ...]     # folders holding run.json
    scripts/registration-stats.py /tmp/runs/*                # e.g. every run of an explore loop
    scripts/registration-stats.py SWEEP_DIR                  # a `vantage bench` folder: every
                                                             # trial's rows in scans.csv/trials/
    scripts/registration-stats.py --by scene SWEEP_DIR       # ... one report per scene (or any
                                                             # scans.csv column: method, trial)

Over every scan after each run's first (the first defines the map frame and is exact), by two
measures of a pose's error: the sensor's position error, and the displacement of the scan's
points (root mean square; how far the map's points land from where they belong, which a turn
moves more than the sensor's position at range). For each: the error of the pose used after
registration (median, 95th percentile, worst), the worst worsening (after minus before; > 0
means registration moved the pose away from the truth), and how many scans got worse by more
than 1 mm; then the median registration time per scan. Runs written before the displacement was
recorded report the position error alone. "final"
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
    "integrate_seconds,reference_seconds,displacement_before_m,displacement_after_m,"
    "displacement_final_m").split(",")


def errors(before, after, final, seconds, displacement=None):
    """One scan's row: the position errors (before, after, final) [m], the registration time [s],
    and the displacements (before, after, final) [m] or None where the run did not record them."""
    return {"position": (before, after, final), "seconds": seconds, "displacement": displacement}


def add_sweep(folder, groups, by=None):
    """Adds the rows of a `vantage bench` folder (its scans.csv, or its trials/*.csv), which keep
    the pose errors and registration times in their columns, in one group or one per value of
    the column `by`; False if it is no sweep folder."""
    files = [folder / "scans.csv"] if (folder / "scans.csv").is_file() else \
        sorted((folder / "trials").glob("*.csv")) if (folder / "trials").is_dir() else []
    if not files:
        return False
    for f in files:
        with open(f, newline="") as handle:
            # NOTE: a trial's file is rows only, under scans.csv's header (README, vantage explore)
            first = handle.readline()
            handle.seek(0)
            names = None if first.startswith("scene,") else SCANS_CSV_HEADER
            for r in csv.DictReader(handle, fieldnames=names):
                if int(r["scan"]) < 2 or "pose_error_final_m" not in r:
                    continue
                if by is not None and by not in r:
                    sys.exit(f"registration-stats: --by {by}: no such column in {f}")
                label = f"sweep {folder.name}" + (f" {by}={r[by]}" if by else "")
                rows = groups.setdefault(label, [])
                displacement = None
                if r.get("displacement_final_m"):
                    displacement = tuple(float(r[f"displacement_{k}_m"])
                                         for k in ("before", "after", "final"))
                rows.append(errors(float(r["pose_error_before_m"]), float(r["pose_error_after_m"]),
                                   float(r["pose_error_final_m"]), float(r["register_seconds"]),
                                   displacement))
    return True


def main(argv):
    by = None
    if len(argv) > 2 and argv[1] == "--by":
        by, argv = argv[2], argv[:1] + argv[3:]
    if len(argv) < 2:
        sys.exit(__doc__)
    groups = {}
    for arg in argv[1:]:
        if add_sweep(Path(arg), groups, by):
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
            displacement = None
            if "displacement_final_m" in e:
                displacement = tuple(e[f"displacement_{k}_m"] for k in ("before", "after", "final"))
            rows.append(errors(e["before_m"], e["after_m"], e.get("final_m", e["after_m"]),
                               scan["seconds"]["register"], displacement))
    for kind, rows in sorted(groups.items()):
        print(f"{kind}: {len(rows)} registered scans from {len(argv) - 1} runs")
        report("sensor position", [r["position"] for r in rows])
        if all(r["displacement"] is not None for r in rows):
            report("points' displacement", [r["displacement"] for r in rows])
        seconds = [r["seconds"] for r in rows]
        print(f"  registration time  median {1e3 * percentile(seconds, 0.5):.1f} ms"
              f"  p95 {1e3 * percentile(seconds, 0.95):.1f} ms per scan")


def report(measure, triples):
    """Prints the figures of one error measure over (before, after, final) triples [m]."""
    print(f"  {measure}:")
    for name, values in (("before", [t[0] for t in triples]), ("after", [t[1] for t in triples]),
                         ("final", [t[2] for t in triples])):
        print(f"    {name:6s}  median {1e3 * percentile(values, 0.5):7.2f} mm"
              f"  p95 {1e3 * percentile(values, 0.95):7.2f} mm"
              f"  worst {1e3 * max(values):7.2f} mm")
    again = sum(f < a - 1e-9 for _, a, f in triples)
    worse = [max(a, f) - b for b, a, f in triples]
    print(f"    {again} scans registered again; worst worsening {1e3 * max(worse):+.2f} mm;"
          f" scans made worse by > 1 mm: {sum(w > 1e-3 for w in worse)}")

if __name__ == "__main__":
    main(sys.argv)
