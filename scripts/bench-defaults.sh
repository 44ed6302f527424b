#!/usr/bin/env bash
# The decision with no search option, through the CLI, as a user runs it (issue 35's targets,
# issue 52's worst case; BENCHMARK.md, "One planner"): explore on a table top (the decisions for
# scans 2-8 by the default method, by the survival reading and by the paper's literal one; scans
# 2-14 on the hemisphere by the default), plan over 200 and 1 000 sphere views of its map after
# one scan, plan on the shared Kinect and stereo frames and on a three-frame recording made from
# the Kinect frame (tests/data/make_recordings.py), and FR-079 with frontier candidates and
# Latombe; then Python's plan with its defaults on the same Kinect frame. Prints each decision's
# seconds.plan [ms] (less greedy's reference, which the decision does not need) and the search
# that decided, run by run; then, row by row, the median of each run and the worst decision of all
# runs (explore: the slowest decision of any run; plan: the slowest run), since a robot waits for
# every decision. Every figure goes with the machine, its load and the yardstick of the same run
# (`vantage_bench --benchmark_filter=BM_Gain30_OctoMap/2`), which this script does not run.
#
#   scripts/bench-defaults.sh [BUILD_DIR] [RUNS] [SCENE]   # build/release, 3 runs, tabletop-4
#
# SCENE is what explore and the sphere views run on: a built-in table top or a scene file, e.g. a
# generated pile no change was tuned on (`vantage scene generate --seed 101 --out pile.yaml`).
# Any build of the CLI will do, an older one too (its JSON may not say which search decided: -),
# so that the defaults before and after a change are measured by one command.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
runs=${2:-3}
scene=${3:-tabletop-4}
vantage="$build/apps/vantage/vantage"
data=tests/data/real
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
threads=2
name=$(basename "$scene" .yaml)
# One line a decision measured: row, run, milliseconds (the summary reads them).
times="$work/times.tsv"
: >"$times"

# The shared frames' manifests, as tests/cli/plan_real.sh writes them.
sed "s|file: milk_cartoon|file: $PWD/$data/milk_cartoon|" "$data/milk.yaml" >"$work/milk.yaml"
cat >"$work/mug.yaml" <<YAML
clouds: [{file: $PWD/$data/table_scene_mug_stereo_textured.pcd}]
sensor: {frame: optical, fov_deg: {horizontal: 60, vertical: 45}, min_range: 0.4, max_range: 3.0}
roi: {min: [-0.4, -0.4, 0.7], max: [0.4, 0.4, 1.1]}
resolution: 0.01
options: {table_segmentation: true, skip_non_finite: true}
YAML
# The recording: three depth frames of the Kinect frame's scene from known poses (TUM RGB-D).
recording=
if /usr/bin/python3 tests/data/make_recordings.py "$work/recording" >/dev/null 2>&1; then
  recording="$work/recording/tum.yaml"
fi
"$vantage" explore --scene "$scene" --scans 1 --threads "$threads" --no-plots --quiet \
  --out "$work/one" >/dev/null

echo "lscpu: $(lscpu | sed -n 's/^Model name: *//p'); load: $(cut -d' ' -f1-3 /proc/loadavg)"
report() {  # NAME FILE RUN: a plan.json's decision
  /usr/bin/python3 - "$1" "$2" "$3" "$times" <<'PY'
import json, sys
name, path, run, times = sys.argv[1:]
p = json.load(open(path))
s = p["seconds"]
ms = 1e3 * (s["plan"] - s["reference"])
print(f"{name:<40} {ms:8.1f} ms  {p.get('search', '-'):<10} "
      f"{len(p['candidates'])} views, chose {p['next_best_view']['index']}")
open(times, "a").write(f"{name}\t{run}\t{ms}\n")
PY
}
for r in $(seq "$runs"); do
  # The default (latombe+surface) on the ring and on the arm's 187-view hemisphere, the survival
  # reading, and the paper's literal method, which ranks by bits.
  for variant in default default-hemisphere survival probabilistic; do
    args=(--scans 8)
    case $variant in
      default) ;;
      default-hemisphere)
        args=(--scans 14 --candidates hemisphere --hemisphere-radii 0.9,1.1,1.3 --view-spacing 0.3) ;;
      *) args+=(--method "$variant") ;;
    esac
    "$vantage" explore --scene "$scene" "${args[@]}" --threads "$threads" \
      --no-plots --quiet --out "$work/explore-$variant-$r" >/dev/null
    /usr/bin/python3 - "$work/explore-$variant-$r/run.json" "explore $name, $variant" "$r" \
      "$times" <<'PY'
import json, statistics, sys
path, name, run, times = sys.argv[1:]
run_json = json.load(open(path))
# NOTE: scan k's record holds the decision that chose it; the first scan's had none.
decided = [s for s in run_json["scans"] if s["scan"] > 1]
ms = [1e3 * (s["seconds"]["plan"] - s["seconds"]["reference"]) for s in decided]
searches = sorted({s.get("search") or "-" for s in decided})
print(f"{name:<40} {statistics.median(ms):8.1f} ms  "
      f"{','.join(searches):<10} median of scans 2-{len(run_json['scans'])} (max {max(ms):.1f}), "
      f"{run_json['config']['method']}, views {[s['view'] for s in run_json['scans']]}")
with open(times, "a") as out:
    for m in ms:
        out.write(f"{name}\t{run}\t{m}\n")
PY
  done
  for n in 200 1000; do
    "$vantage" plan --map "$work/one/map.ot" --candidates sphere --views "$n" \
      --threads "$threads" --no-plots --json --out "$work/sphere$n-$r" >/dev/null
    report "plan, $n sphere views" "$work/sphere$n-$r/plan.json" "$r"
  done
  for frame in milk mug; do
    "$vantage" plan "$work/$frame.yaml" --threads "$threads" --no-plots --json \
      --out "$work/$frame-$r" >/dev/null
    report "plan, $frame frame" "$work/$frame-$r/plan.json" "$r"
  done
  if [[ -n $recording ]]; then
    "$vantage" plan "$recording" --threads "$threads" --no-plots --json \
      --out "$work/recording-$r" >/dev/null
    report "plan, Kinect recording (3 frames)" "$work/recording-$r/plan.json" "$r"
  fi
  for band in any 0.5; do
    height=()
    [[ $band == any ]] || height=(--sensor-height "$band")
    "$vantage" plan --map "$data/geb079.bt" --candidates frontier "${height[@]}" \
      --method latombe --pose 0,0,0.5,0,0,0 --threads "$threads" --no-plots --json \
      --out "$work/fr079-$band-$r" >/dev/null
    report "plan, FR-079 frontier ($band m), latombe" "$work/fr079-$band-$r/plan.json" "$r"
  done
  # Python's plan_next_view with its defaults, on the Kinect frame's map and plan's candidates.
  compgen -G "$build/python/vantage/_vantage*.so" >/dev/null || continue  # no bindings built
  PYTHONPATH="$build/python" /usr/bin/python3 - "$work/milk-$r" "$r" "$times" <<'PY'
import json, sys
import numpy as np
import vantage as vt
folder, run, times = sys.argv[1:]
cli = json.load(open(f"{folder}/plan.json"))
grid = vt.OccupancyGrid.load(f"{folder}/map.ot")
poses = []
for c in cli["candidates"]:
    x, y, z, w = c["sensor"]["quaternion_xyzw"]
    pose = np.eye(4)
    pose[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                    [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    pose[:3, 3] = c["sensor"]["position"]
    poses.append((c["index"], pose))
s = cli["sensor"]
fov = vt.SensorFov.from_degrees(s["horizontal_fov_deg"], s["vertical_fov_deg"], s["min_range_m"],
                                s["max_range_m"])
poses = [p for _, p in sorted(poses, key=lambda ip: ip[0])]
# NOTE: the CLI's robot (the last cloud's pose), so that the default weighs the same travel.
x, y, z, w = cli["robot"]["sensor"]["quaternion_xyzw"]
robot = np.eye(4)
robot[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
robot[:3, 3] = cli["robot"]["sensor"]["position"]
plan = vt.plan_next_view(grid, np.stack(poses), fov, robot=robot)
print(f"{'python, milk frame':<40} {1e3 * plan.seconds:8.1f} ms  "
      f"{getattr(plan, 'search', '-'):<10} "
      f"{len(poses)} views, the CLI's choice: {plan.best == cli['next_best_view']['index']}")
open(times, "a").write(f"python, milk frame\t{run}\t{1e3 * plan.seconds}\n")
PY
done
# Row by row: each run's median and the worst decision of all runs.
echo
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$times" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    name, run, ms = line.rstrip("\n").split("\t")
    rows.setdefault(name, {}).setdefault(run, []).append(float(ms))
print(f"{'decision [ms]':<40} {'median, run by run':<28} worst of all runs")
for name, by_run in rows.items():
    medians = ", ".join(f"{statistics.median(v):.1f}" for v in by_run.values())
    worst = max(max(v) for v in by_run.values())
    print(f"{name:<40} {medians:<28} {worst:.1f}")
PY
