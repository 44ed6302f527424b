#!/usr/bin/env bash
# The work budget's calibration (docs/robustness.md, "Work"): each decision's estimate
# (plan.json's seconds.estimate) against the time it took (seconds.plan), on a grid of 80^3 cells of 12.5 mm that a sensor looking away left unobserved:
# the worst case, where every walk goes the whole way. measured/estimate must stay below 1.
# Usage: scripts/calibrate-work.sh [path/to/vantage] [OUT_DIR]
set -euo pipefail
vantage=${1:-$(dirname "$0")/../build/release/apps/vantage/vantage}
out=${2:-$(mktemp -d)}
mkdir -p "$out"
cat >"$out/front.pcd" <<'PCD'
VERSION 0.7
FIELDS x y z
SIZE 4 4 4
TYPE F F F
COUNT 1 1 1
WIDTH 3
HEIGHT 1
VIEWPOINT 0 0 0 1 0 0 0
POINTS 3
DATA ascii
1 0 0
1.1 0.1 0
1.2 0 0.1
PCD
# The sensor looks along -x, away from the roi: nothing is mapped, every cell stays unobserved.
cat >"$out/away.yaml" <<'YAML'
clouds: [{file: front.pcd, pose: [-1, 0, 0, 0,  0, -1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}]
sensor: {frame: x_forward, fov_deg: {horizontal: 60, vertical: 45}, min_range: 0.1, max_range: 3.0}
roi: {min: [0.5, -0.5, -0.5], max: [1.5, 0.5, 0.5]}
resolution: 0.0125
options: {table_segmentation: false, icp: false}
YAML
printf '%-58s %12s %12s %8s\n' "decision" "estimate [s]" "took [s]" "ratio"
run() {
  local name=$1
  shift
  rm -rf "$out/run"
  "$vantage" plan "$out/away.yaml" "$@" --no-plots --json --max-work 1e9 --out "$out/run" \
    >"$out/plan.json" 2>/dev/null
  local value took
  value=$(python3 -c "import json; print(json.load(open('$out/plan.json'))['seconds']['estimate'])")
  took=$(python3 -c "import json; print(json.load(open('$out/plan.json'))['seconds']['plan'])")
  printf '%-58s %12.3f %12.3f %8.2f\n' "$name" "$value" "$took" "$(python3 -c "print($took / $value)")"
}
run "swept, survival: 3 000 views" --candidates ring --views 1000
run "swept, survival: 30 000 views" --candidates ring --views 10000
run "exhaustive, survival: 30 views (greedy reference too)" --search exhaustive
run "exhaustive, greedy: 30 views" --method greedy --search exhaustive
run "pruned, probabilistic: 30 views (greedy reference too)" --method probabilistic
run "sequence: 30 views, K = 3" --method sequence
run "exhaustive, unobserved-voxel: 30 views" --method unobserved-voxel
uptime
