#!/usr/bin/env bash
# issue 50: scripts/slurm-sweep.sh without a Slurm: its command line (exit 2 on a bad one, 1 on a
# folder it did not make), and the array script it writes, run by stand-ins for sbatch and vantage
# that record what they are given: sbatch's options passed through, and each task's vantage
# command with the sweep's options as given (spaces and all), its shard, its folder and its mark.
# Usage: slurm_sweep_usage.sh SOURCE_DIR WORK_DIR
set -euo pipefail
script=$1/scripts/slurm-sweep.sh
work=$2
rm -rf "$work"
mkdir -p "$work/bin"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# expect CODE TEXT ARGS...: the script exits CODE and says TEXT on stderr.
expect() {
  local code=$1 text=$2 got=0
  shift 2
  "$script" "$@" >/dev/null 2>"$work/err" || got=$?
  [[ $got -eq $code ]] || fail "slurm-sweep.sh $* exited $got, not $code: $(cat "$work/err")"
  grep -qF -- "$text" "$work/err" || fail "slurm-sweep.sh $* said '$(cat "$work/err")', not '$text'"
}
cat >"$work/bin/vantage" <<'SH'
#!/usr/bin/env bash
printf '%s\n' "$@" >"$(dirname "$0")/../vantage-args"
SH
cat >"$work/bin/sbatch" <<'SH'
#!/usr/bin/env bash
printf '%s\n' "$@" >>"$(dirname "$0")/../sbatch-args"
echo 42
SH
chmod +x "$work/bin/vantage" "$work/bin/sbatch"
export PATH=$work/bin:$PATH

expect 2 "give a command"
expect 2 "unknown command 'go'" go
expect 2 "--tasks must be a whole number" submit --out "$work/s" -- tabletop
expect 2 "--out DIR is needed" submit --tasks 2 -- tabletop
expect 2 "starts with tabletop or office, not 'explore'" submit --tasks 2 --out "$work/s" -- explore
expect 2 "the script sets --shard itself" submit --tasks 2 --out "$work/s" -- tabletop --shard 0/2
expect 2 "the script sets --out itself" submit --tasks 2 --out "$work/s" -- tabletop --out x
expect 2 "--partition needs a value" submit --tasks 2 --out "$work/s" --partition
expect 2 "give the sweep after --" submit --tasks 2 --out "$work/s"
expect 1 "no slurm/settings" merge "$work"
"$script" --help | grep -q "submit --tasks N --out DIR" || fail "--help does not say how to submit"

# submit: the array script, and sbatch's options.
sweep="$work/s w"
[[ $("$script" submit --tasks 3 --out "$sweep" --partition p1 --time 1:00:00 --cpus-per-task 2 \
  --mem 4G --sbatch-arg --account=lab --parsable -- tabletop --scenes "a b.yaml" --scans 3) == 42 ]] ||
  fail "submit --parsable did not print sbatch's job id"
for line in "--array=0-2" "--partition=p1" "--time=1:00:00" "--cpus-per-task=2" "--mem=4G" \
  "--account=lab" "--open-mode=append"; do
  grep -qx -- "#SBATCH $line" "$sweep/slurm/sweep.sbatch" || fail "the array script lacks #SBATCH $line"
done
grep -qx -- "--array=0-2" "$work/sbatch-args" || fail "sbatch was not given the whole array"
SLURM_ARRAY_TASK_ID=1 bash "$sweep/slurm/sweep.sbatch"
expected=(bench tabletop --scenes "a b.yaml" --scans 3 --jobs 2 --no-plots --shard 1/3 --out
          "$(realpath "$sweep")/shard-1")
[[ $(cat "$work/vantage-args") == "$(printf '%s\n' "${expected[@]}")" ]] ||
  fail "task 1 ran vantage $(tr '\n' ' ' <"$work/vantage-args")"
[[ -f $sweep/slurm/task-1.done ]] || fail "task 1 did not mark itself done"

# resubmit: the tasks without their mark, or those named; merge waits for all.
: >"$work/sbatch-args"
"$script" resubmit "$sweep" >/dev/null
grep -qx -- "--array=0,2" "$work/sbatch-args" || fail "resubmit did not ask for tasks 0 and 2"
expect 2 "task 3 is not one of the sweep's 0..2" resubmit "$sweep" --tasks 3
expect 1 "task(s) 0,2 not done" merge "$sweep" --no-plots
echo "ok: the command line and the array script"
