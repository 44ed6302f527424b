#!/usr/bin/env bash
# Fingerprints what the vantage binary decides and measures, so that a change meant to keep
# behaviour can prove it did: run it before and after, then diff the two folders.
#
#   scripts/same-output.sh OUT_DIR [VANTAGE_BINARY]
#   diff -r before/ after/ && echo identical
#
# Runs `make demo`'s exploration and short runs of every method, evaluation and scene kind, and
# keeps each scans.csv without its wall-clock columns (plan_seconds, the stage times) and each run.json without its
# timings and version. Everything else (views, predictions, actual gains, unobserved cells,
# coverage, poses, ICP errors) must match to the last digit.
set -euo pipefail
out=${1:?usage: same-output.sh OUT_DIR [VANTAGE_BINARY]}
bin=${2:-build/release/apps/vantage/vantage}
[[ -x "$bin" ]] || { echo "same-output: no binary at $bin (build first)" >&2; exit 1; }
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {
  local name=$1
  shift
  "$bin" explore --quiet --no-plots --threads 2 --out "$work/$name" "$@" >/dev/null
  # Column 12 of scans.csv is plan_seconds, and 21 on are the stage times: the wall-clock columns.
  cut -d, -f1-11,13-20 "$work/$name/scans.csv" >"$out/$name.csv"
  /usr/bin/python3 - "$work/$name/run.json" >"$out/$name.json" <<'PY'
import json, sys
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items()
                if k not in ("seconds", "vantage_version", "threads", "num_threads", "out")}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
print(json.dumps(strip(json.load(open(sys.argv[1]))), indent=1, sort_keys=True))
PY
}

run demo                                                  # make demo's exploration
run tt4-greedy    --scene tabletop-4 --method greedy --scans 4 --seed 3
run tt1-random    --scene tabletop-1 --method random --scans 3 --seed 5
run tt2-exact     --scene tabletop-2 --evaluation exact --scans 3 --start 4
run tt3-revisit   --scene tabletop-3 --revisit --scans 4 --alpha 0.9999
run office-prob   --scene office-small-cluttered --scans 3
run office-yama   --scene office-small-sparse --method yamauchi --scans 3
run office-latom  --scene office-small-cluttered --method latombe --scans 3 --start 1
echo "same-output: $(ls "$out" | wc -l) files in $out"
