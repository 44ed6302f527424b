#!/usr/bin/env bash
# A tiny sweep with two jobs, the parallel path of `vantage bench` (the tsan preset runs it under
# ThreadSanitizer, docs/fuzzing.md): it must finish, and its scans.csv must hold a header and one
# row per scan of every trial, the same rows as one job gives.
# Usage: bench_jobs.sh VANTAGE SCENE WORK_DIR
set -euo pipefail
vantage=$1
scene=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
sweep() {
  "$vantage" bench tabletop --scenes "$scene" --methods probabilistic,greedy --trials 2 --scans 2 \
    --jobs "$1" --no-plots --out "$work/jobs$1" >/dev/null
}
sweep 2
sweep 1
rows=$(wc -l <"$work/jobs2/scans.csv")
[[ $rows -eq $((1 + 2 * 2 * 2)) ]] || { echo "FAIL: scans.csv has $rows lines, expected 9"; exit 1; }
# Timing columns differ from run to run; everything else must not.
strip() { /usr/bin/python3 -c '
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
keep = [i for i, name in enumerate(rows[0]) if not name.endswith("_seconds")]
for row in sorted(rows[1:]):
    print(",".join(row[i] for i in keep))' "$1"; }
if ! diff <(strip "$work/jobs1/scans.csv") <(strip "$work/jobs2/scans.csv") >/dev/null; then
  echo "FAIL: two jobs wrote other rows than one"; exit 1
fi
echo "ok: $rows lines, the same for 1 and 2 jobs"
