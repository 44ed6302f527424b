#!/usr/bin/env bash
# The decision with no search option, through the CLI, as a user runs it (issue 35's targets;
# BENCHMARK.md, "One planner"): explore on tabletop-4 (the decisions for scans 2-8 by the default
# method, by the survival reading and by the paper's literal one; scans 2-14 on the hemisphere by
# the default), plan over
# 200 and 1 000 sphere views of tabletop-4's map after one scan, plan on the shared Kinect and
# stereo frames, and FR-079 with frontier candidates and Latombe; then Python's plan with its
# defaults on the same Kinect frame. Prints each decision's seconds.plan [ms] (less greedy's
# reference, which the decision does not need) and the search that decided. Every figure goes with
# the machine, its load and the yardstick of the same run (`vantage_bench
# --benchmark_filter=BM_Gain30_OctoMap/2`), which this script does not run.
#
#   scripts/bench-defaults.sh [BUILD_DIR] [RUNS]      # default build/release, 3 runs each
#
# Any build of the CLI will do, an older one too (its JSON may not say which search decided: -),
# so that the defaults before and after a change are measured by one command.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
runs=${2:-3}
vantage="$build/apps/vantage/vantage"
data=tests/data/real
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
threads=2

# The shared frames' manifests, as tests/cli/plan_real.sh writes them.
sed "s|file: milk_cartoon|file: $PWD/$data/milk_cartoon|" "$data/milk.yaml" >"$work/milk.yaml"
cat >"$work/mug.yaml" <<YAML
clouds: [{file: $PWD/$data/table_scene_mug_stereo_textured.pcd}]
sensor: {frame: optical, fov_deg: {horizontal: 60, vertical: 45}, min_range: 0.4, max_range: 3.0}
roi: {min: [-0.4, -0.4, 0.7], max: [0.4, 0.4, 1.1]}
resolution: 0.01
options: {table_segmentation: true, skip_non_finite: true}
YAML
"$vantage" explore --scene tabletop-4 --scans 1 --threads "$threads" --no-plots --quiet \
  --out "$work/one" >/dev/null

echo "lscpu: $(lscpu | sed -n 's/^Model name: *//p'); load: $(cut -d' ' -f1-3 /proc/loadavg)"
report() {  # NAME FILE: a plan.json's decision
  /usr/bin/python3 - "$1" "$2" <<'PY'
import json, sys
p = json.load(open(sys.argv[2]))
s = p["seconds"]
print(f"{sys.argv[1]:<34} {1e3 * (s['plan'] - s['reference']):8.1f} ms  "
      f"{p.get('search', '-'):<10} "
      f"{len(p['candidates'])} views, chose {p['next_best_view']['index']}")
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
    "$vantage" explore --scene tabletop-4 "${args[@]}" --threads "$threads" \
      --no-plots --quiet --out "$work/explore-$variant-$r" >/dev/null
    /usr/bin/python3 - "$work/explore-$variant-$r/run.json" "$variant" <<'PY'
import json, statistics, sys
run = json.load(open(sys.argv[1]))
# NOTE: scan k's record holds the decision that chose it; the first scan's had none.
decided = [s for s in run["scans"] if s["scan"] > 1]
ms = [1e3 * (s["seconds"]["plan"] - s["seconds"]["reference"]) for s in decided]
searches = sorted({s.get("search") or "-" for s in decided})
print(f"{'explore tabletop-4, ' + sys.argv[2]:<34} {statistics.median(ms):8.1f} ms  "
      f"{','.join(searches):<10} median of scans 2-{len(run['scans'])} (max {max(ms):.1f}), "
      f"{run['config']['method']}, views {[s['view'] for s in run['scans']]}")
PY
  done
  for n in 200 1000; do
    "$vantage" plan --map "$work/one/map.ot" --candidates sphere --views "$n" \
      --threads "$threads" --no-plots --json --out "$work/sphere$n-$r" >/dev/null
    report "plan, $n sphere views" "$work/sphere$n-$r/plan.json"
  done
  for frame in milk mug; do
    "$vantage" plan "$work/$frame.yaml" --threads "$threads" --no-plots --json \
      --out "$work/$frame-$r" >/dev/null
    report "plan, $frame frame" "$work/$frame-$r/plan.json"
  done
  for band in any 0.5; do
    height=()
    [[ $band == any ]] || height=(--sensor-height "$band")
    "$vantage" plan --map "$data/geb079.bt" --candidates frontier "${height[@]}" \
      --method latombe --pose 0,0,0.5,0,0,0 --threads "$threads" --no-plots --json \
      --out "$work/fr079-$band-$r" >/dev/null
    report "plan, FR-079 frontier ($band m), latombe" "$work/fr079-$band-$r/plan.json"
  done
  # Python's plan_next_view with its defaults, on the Kinect frame's map and plan's candidates.
  compgen -G "$build/python/vantage/_vantage*.so" >/dev/null || continue  # no bindings built
  PYTHONPATH="$build/python" /usr/bin/python3 - "$work/milk-$r" <<'PY'
import json, sys
import numpy as np
import vantage as vt
folder = sys.argv[1]
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
print(f"{'python, milk frame':<34} {1e3 * plan.seconds:8.1f} ms  "
      f"{getattr(plan, 'search', '-'):<10} "
      f"{len(poses)} views, the CLI's choice: {plan.best == cli['next_best_view']['index']}")
PY
done
