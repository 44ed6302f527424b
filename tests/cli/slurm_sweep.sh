#!/usr/bin/env bash
# issue 50: a sweep as a Slurm job array, against a real Slurm started on this host
# (local_slurm.sh; root, as CI runs). A tiny sweep runs once on one machine and once as an array
# of 4 tasks through scripts/slurm-sweep.sh; one task is cancelled in the middle of a trial (after
# its first trial file, before its last), resubmitted, and the shards are merged. Every result
# file of the merged folder must equal the one machine's byte for byte: sweep.json and the
# yardstick files as they are, scans.csv and the trial files without their *_seconds columns
# (wall times). Fails, never skips, when Slurm cannot start. Stops the daemons it started.
# Usage: slurm_sweep.sh VANTAGE SCENE SOURCE_DIR WORK_DIR
set -euo pipefail
vantage=$1
scene=$2
source_dir=$3
work=$4
sweep_script=$source_dir/scripts/slurm-sweep.sh
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
started=$(date +%s)
rm -rf "$work"
mkdir -p "$work"
# shellcheck source=tests/cli/local_slurm.sh
source "$source_dir/tests/cli/local_slurm.sh"
trap local_slurm_stop EXIT
trap 'exit 1' INT TERM
local_slurm_start "$work/slurm" || fail "Slurm did not start (its logs: $work/slurm/log)"
echo "slurm: up in $(($(date +%s) - started)) s"

# 12 trials, 3 a task: the cancelled task has two trials left when its first is written.
tasks=4
# shellcheck disable=SC2054 # a comma-separated list of methods, one argument
sweep=(tabletop --scenes "$scene" --methods probabilistic,greedy --trials 6 --scans 5)
"$vantage" bench "${sweep[@]}" --no-plots --out "$work/one" >/dev/null

cluster=$work/cluster
job=$("$sweep_script" submit --tasks $tasks --out "$cluster" --vantage "$vantage" \
  --partition test --time 10 --cpus-per-task 1 --mem 512M --parsable -- "${sweep[@]}")
[[ $job =~ ^[0-9]+$ ]] || fail "submit printed '$job', not a job id"

# Polls "$@" every 0.05 s, at most $1 times.
poll() {
  local tries=$1
  shift
  for ((k = 0; k < tries; ++k)); do
    "$@" && return 0
    sleep 0.05
  done
  return 1
}
trials_of() { find "$cluster/shard-$1/trials" -name '*.csv' 2>/dev/null | wc -l; }
array_ended() { [[ -z $(squeue -h -j "$job" 2>/dev/null) ]]; }
victim=1
victim_started() { [[ $(trials_of $victim) -ge 1 ]]; }
poll 6000 victim_started ||
  fail "task $victim wrote no trial file in 300 s (log: $cluster/slurm/task-$victim.log)"
scancel "${job}_$victim"
poll 12000 array_ended || fail "the array did not end in 600 s: $(squeue -j "$job" 2>&1)"

kept=$(trials_of $victim)
share=$((12 / tasks))
[[ $kept -ge 1 && $kept -lt $share ]] ||
  fail "task $victim held $kept of its $share trials when cancelled: not in the middle of its trials"
[[ ! -f $cluster/slurm/task-$victim.done ]] || fail "the cancelled task $victim was marked done"
for ((t = 0; t < tasks; ++t)); do
  [[ $t -eq $victim || -f $cluster/slurm/task-$t.done ]] ||
    fail "task $t did not finish (log: $cluster/slurm/task-$t.log)"
done
# Merging before the cancelled task is redone is refused, naming it.
if out=$("$sweep_script" merge "$cluster" --no-plots 2>&1); then
  fail "merge ran with task $victim undone"
fi
[[ $out == *"task(s) $victim not done"* ]] || fail "merge said '$out', not that task $victim is undone"

# Resubmitted, the task resumes: its kept trials are skipped, the rest run.
again=$("$sweep_script" resubmit "$cluster" --wait --parsable) ||
  fail "the resubmitted task $victim failed (log: $cluster/slurm/task-$victim.log)"
[[ -f $cluster/slurm/task-$victim.done ]] || fail "the resubmitted task $victim is not done"
[[ $(grep -c "done before, skipped" "$cluster/slurm/task-$victim.log") -eq $kept ]] ||
  fail "the resubmitted task did not skip its $kept kept trial(s)"
"$sweep_script" merge "$cluster" --no-plots >/dev/null

# The merged folder's result files (its shard and slurm folders aside) against the one machine's.
/usr/bin/python3 - "$work/one" "$cluster" <<'PY' || exit 1
import os, sys

one, merged = sys.argv[1], sys.argv[2]

def files(top, skip):
    found = set()
    for root, dirs, names in os.walk(top):
        if root == top:
            dirs[:] = [d for d in dirs if not d.startswith("shard-") and d not in skip]
        found |= {os.path.relpath(os.path.join(root, n), top) for n in names}
    return found

a, b = files(one, set()), files(merged, {"slurm"})
if a != b:
    sys.exit(f"FAIL: the merged folder holds other files: only one machine's {sorted(a - b)}, "
             f"only the merged {sorted(b - a)}")
header = open(os.path.join(one, "scans.csv"), "rb").readline().rstrip(b"\n").split(b",")
timeless = [i for i, name in enumerate(header) if not name.endswith(b"_seconds")]

def without_times(data):
    lines = data.split(b"\n")
    return b"\n".join(b",".join(line.split(b",")[i] for i in timeless) if line else line
                      for line in lines)

for name in sorted(a):
    x = open(os.path.join(one, name), "rb").read()
    y = open(os.path.join(merged, name), "rb").read()
    if name.endswith(".csv"):
        x, y = without_times(x), without_times(y)
    if x != y:
        sys.exit(f"FAIL: {name} differs between the one machine's sweep and the merged array's")
rows = open(os.path.join(merged, "scans.csv")).read().count("\n") - 1
print(f"ok: {len(a)} result files equal, scans.csv {rows} rows")
PY
echo "ok: array of $tasks, task $victim cancelled after $kept trial(s) and resubmitted (job $again), in $(($(date +%s) - started)) s"
