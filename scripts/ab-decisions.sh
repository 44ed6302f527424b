#!/usr/bin/env bash
# Issue 52's two slowest rows, two builds in turn (BENCHMARK.md): the default explore on the ring
# of tabletop-4 (every decision for scans 2-8) and `plan` among 200 sphere views of its map after
# one scan (three runs), the decision alone [ms] as scripts/bench-defaults.sh counts it
# (seconds.plan less greedy's reference), 2 threads; A, B, A, B, ... so that a change of load
# falls on both. Prints the machine and the load beside each; run the yardstick
# (`vantage_bench --benchmark_filter=BM_Gain30_OctoMap/2`) beside it.
#
#   scripts/ab-decisions.sh BUILD_A BUILD_B [RUNS]   # e.g. ../before/build/release build/release 3
set -euo pipefail
a="$1/apps/vantage/vantage"
b="$2/apps/vantage/vantage"
runs=${3:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "lscpu: $(lscpu | sed -n 's/^Model name: *//p'); A: $a; B: $b"
"$a" explore --scene tabletop-4 --scans 1 --threads 2 --no-plots --quiet --out "$work/one" >/dev/null
decision_ms() {  # FILE: each decision of a run.json or plan.json [ms]
  /usr/bin/python3 - "$1" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
seconds = [s["seconds"] for s in j["scans"] if s["scan"] > 1] if "scans" in j else [j["seconds"]]
print(" ".join(f"{1e3 * (s['plan'] - s['reference']):.1f}" for s in seconds))
PY
}
for r in $(seq "$runs"); do
  for name in A B; do
    bin=$a
    [[ $name == B ]] && bin=$b
    rm -rf "$work/ring"
    "$bin" explore --scene tabletop-4 --scans 8 --threads 2 --no-plots --quiet \
      --out "$work/ring" >/dev/null
    sphere=()
    for k in 1 2 3; do
      rm -rf "$work/sphere"
      "$bin" plan --map "$work/one/map.ot" --candidates sphere --views 200 --threads 2 \
        --no-plots --json --out "$work/sphere" >/dev/null
      sphere+=("$(decision_ms "$work/sphere/plan.json")")
    done
    echo "$name load $(cut -d' ' -f1 /proc/loadavg)  ring scans 2-8: $(decision_ms "$work/ring/run.json")" \
      " 200 sphere views: ${sphere[*]}"
  done
done
