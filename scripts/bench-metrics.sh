#!/usr/bin/env bash
# The seven metrics' decisions (and the surface model's, issue 37) among the 187 hemisphere views (issue 36, item 4; BENCHMARK.md,
# "The seven metrics at speed"), through the CLI as a user runs them: `vantage explore` on
# tabletop-4, --candidates hemisphere --hemisphere-radii 0.9,1.1,1.3 --view-spacing 0.3 (the
# issue-26 sweeps' candidates), 7 scans on 2 threads, per metric and per build. Prints each
# decision's seconds.plan [ms] (less greedy's reference, which the decision does not need) after
# 1, 3 and 6 scans, the median of the six, the search that decided (with no --search, the swept
# search's race since issue 36 item 4; before, the exhaustive one) and the views chosen; the
# machine, its load and the yardstick (`vantage_bench --benchmark_filter=BM_Gain30_OctoMap/2`, of
# the first build) before and after.
#
#   scripts/bench-metrics.sh [BUILD_DIR...]      # default build/release
set -euo pipefail
cd "$(dirname "$0")/.."
builds=("$@")
[[ ${#builds[@]} -gt 0 ]] || builds=(build/release)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
yardstick() {
  "${builds[0]}/bench/vantage_bench" --benchmark_filter='BM_Gain30_OctoMap/2' 2>&1 |
    awk '/^BM_/ {print "yardstick " $2 " " $3}'
}
echo "lscpu: $(lscpu | sed -n 's/^Model name: *//p'); $(nproc) CPUs;" \
  "load: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%H:%M) UTC"
yardstick
for method in occlusion-aware unobserved-voxel rear-side-voxel rear-side-entropy proximity-count \
  average-entropy area-factor surface; do
  for build in "${builds[@]}"; do
    out="$work/$method-$(echo "$build" | tr / _)"
    "$build/apps/vantage/vantage" explore --scene tabletop-4 --candidates hemisphere \
      --hemisphere-radii 0.9,1.1,1.3 --view-spacing 0.3 --method "$method" --scans 7 --threads 2 \
      --no-plots --quiet --out "$out" >/dev/null
    /usr/bin/python3 - "$out/run.json" "$method" "$build" <<'PY'
import json, statistics, sys
run = json.load(open(sys.argv[1]))
# NOTE: scan k's record holds the decision that chose it; the first scan's had none.
decided = [s for s in run["scans"] if s["scan"] > 1]
ms = [1e3 * (s["seconds"]["plan"] - s["seconds"]["reference"]) for s in decided]
print(f"{sys.argv[2]:<18} {sys.argv[3]:<24} {decided[0]['candidates']} views, "
      f"{decided[0].get('search', '?')} search; after 1, 3, 6 "
      f"scans: {ms[0]:6.0f} {ms[2]:6.0f} {ms[5]:6.0f} ms; median of 6: "
      f"{statistics.median(ms):6.0f} ms; views {[s['view'] for s in run['scans']]}")
PY
  done
done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%H:%M) UTC"
yardstick
