#!/usr/bin/env bash
# Runs a `vantage bench` sweep as a Slurm job array: task i runs shard i of N into DIR/shard-i,
# a task that died is resubmitted (it resumes: finished trials are kept, each written whole), and
# the shards are merged into DIR (README.md, "Sweeps on a cluster").
#
#   scripts/slurm-sweep.sh submit --tasks N --out DIR [--partition P] [--time T]
#       [--cpus-per-task C] [--mem M] [--vantage PATH] [--sbatch-arg ARG]... [--wait] [--parsable]
#       -- tabletop|office [the sweep's options]
#   scripts/slurm-sweep.sh resubmit DIR [--tasks I,J,...] [--wait] [--parsable]
#   scripts/slurm-sweep.sh merge DIR [--no-plots]
#
# submit writes DIR/slurm/sweep.sbatch and submits it as an array of N tasks; each task runs
# `vantage bench KIND ... --shard I/N --out DIR/shard-I --jobs C` (C = --cpus-per-task unless the
# sweep's options give --jobs), logs to DIR/slurm/task-I.log and, when its shard is complete,
# leaves DIR/slurm/task-I.done. resubmit submits the tasks without that mark (or those named), once
# the array has ended. merge checks that every task is done and runs `vantage bench merge` of the
# shards into DIR (plots and summary unless --no-plots). --partition, --time, --cpus-per-task and
# --mem are sbatch's; --sbatch-arg passes any other sbatch option (e.g. --account=lab). DIR must
# be on a file system the nodes share, and the vantage binary (--vantage, default the one on PATH)
# reachable from them at the same path. --wait blocks until the tasks end; --parsable prints only
# the job id. Exit 2 on a bad command line, 1 when a step fails.
set -euo pipefail

usage() {
  echo "slurm-sweep: $1" >&2
  echo "usage: scripts/slurm-sweep.sh submit --tasks N --out DIR [options] -- tabletop|office [sweep options]" >&2
  echo "       scripts/slurm-sweep.sh resubmit DIR [--tasks I,J,...] [--wait] [--parsable]" >&2
  echo "       scripts/slurm-sweep.sh merge DIR [--no-plots]" >&2
  exit 2
}
fail() {
  echo "slurm-sweep: $1" >&2
  exit 1
}
# The value of option $1, which must be there ($2 = how many arguments are left).
need_value() { [[ $2 -ge 2 ]] || usage "$1 needs a value"; }

# DIR/slurm/settings holds what resubmit and merge need: tasks=N and vantage=PATH.
setting() {
  local file=$1/slurm/settings
  [[ -f $file ]] || fail "$1: no slurm/settings, not a folder of scripts/slurm-sweep.sh submit"
  sed -n "s/^$2=//p" "$file"
}

submit_tasks() {  # DIR ARRAY WAIT PARSABLE
  local dir=$1 array=$2 wait=$3 parsable=$4 id
  local args=(--parsable --array="$array")
  [[ $wait == 1 ]] && args+=(--wait)
  id=$(sbatch "${args[@]}" "$dir/slurm/sweep.sbatch") || fail "sbatch refused $dir/slurm/sweep.sbatch"
  id=${id%%;*}  # "ID;CLUSTER" on a federation
  if [[ $parsable == 1 ]]; then
    echo "$id"
  else
    echo "submitted job $id: tasks $array of $(setting "$dir" tasks), logs in $dir/slurm/task-I.log"
    echo "when it has ended: scripts/slurm-sweep.sh merge $dir  (resubmit first if a task died)"
  fi
}

cmd_submit() {
  local tasks="" out="" vantage="" wait=0 parsable=0 cpus=1
  local sbatch_lines=()
  while [[ $# -gt 0 && $1 != -- ]]; do
    case $1 in
      --tasks) need_value "$1" $#; tasks=$2; shift 2 ;;
      --out) need_value "$1" $#; out=$2; shift 2 ;;
      --vantage) need_value "$1" $#; vantage=$2; shift 2 ;;
      --partition | --time | --mem)
        need_value "$1" $#; sbatch_lines+=("$1=$2"); shift 2 ;;
      --cpus-per-task)
        need_value "$1" $#; cpus=$2; sbatch_lines+=("$1=$2"); shift 2 ;;
      --sbatch-arg) need_value "$1" $#; sbatch_lines+=("$2"); shift 2 ;;
      --wait) wait=1; shift ;;
      --parsable) parsable=1; shift ;;
      *) usage "unknown option '$1' (the sweep's options go after --)" ;;
    esac
  done
  [[ $# -gt 0 ]] || usage "give the sweep after --, e.g. -- tabletop --scenes tabletop-1"
  shift
  local sweep=("$@")
  [[ ${#sweep[@]} -gt 0 && ( ${sweep[0]} == tabletop || ${sweep[0]} == office ) ]] ||
    usage "the sweep after -- starts with tabletop or office, not '${sweep[0]:-}'"
  [[ $tasks =~ ^[1-9][0-9]*$ ]] || usage "--tasks must be a whole number of at least 1, not '$tasks'"
  [[ $cpus =~ ^[1-9][0-9]*$ ]] || usage "--cpus-per-task must be a whole number of at least 1, not '$cpus'"
  [[ -n $out ]] || usage "--out DIR is needed"
  [[ $out != *[\"$'\n']* ]] || usage "--out DIR may not hold a double quote or a line break"
  local jobs_given=0 arg
  for arg in "${sweep[@]:1}"; do
    case $arg in
      --shard | --shard=* | --out | --out=* | -o | -o*)
        usage "the script sets $arg itself (--out DIR/shard-I, --shard I/N)" ;;
      --jobs | --jobs=*) jobs_given=1 ;;
    esac
  done
  if [[ -z $vantage ]]; then
    vantage=$(command -v vantage) || usage "no vantage on PATH: give --vantage PATH"
  fi
  [[ -x $vantage ]] || usage "--vantage $vantage is not an executable"
  vantage=$(realpath "$vantage")
  mkdir -p "$out/slurm"
  out=$(realpath "$out")
  local line
  {
    echo "#!/usr/bin/env bash"
    echo "# Written by scripts/slurm-sweep.sh submit: one shard of the sweep per array task."
    echo "#SBATCH --job-name=vantage-bench"
    echo "#SBATCH --array=0-$((tasks - 1))"
    echo "#SBATCH --output=\"$out/slurm/task-%a.log\""
    echo "#SBATCH --open-mode=append"
    for line in "${sbatch_lines[@]}"; do echo "#SBATCH $line"; done
    echo "set -euo pipefail"
    echo "task=\$SLURM_ARRAY_TASK_ID"
    echo "rm -f $(printf '%q' "$out/slurm/task-")\$task.done"
    printf '%q bench' "$vantage"
    printf ' %q' "${sweep[@]}"
    [[ $jobs_given == 1 ]] || printf ' --jobs %s' "$cpus"
    # shellcheck disable=SC2016 # $task is the task's, expanded when it runs
    printf ' --no-plots --shard "$task/%s" --out %q"$task"\n' "$tasks" "$out/shard-"
    echo "touch $(printf '%q' "$out/slurm/task-")\$task.done"
  } >"$out/slurm/sweep.sbatch"
  printf 'tasks=%s\nvantage=%s\n' "$tasks" "$vantage" >"$out/slurm/settings"
  submit_tasks "$out" "0-$((tasks - 1))" "$wait" "$parsable"
}

cmd_resubmit() {
  [[ $# -ge 1 ]] || usage "resubmit needs the sweep's folder"
  local dir=$1 which="" wait=0 parsable=0
  shift
  while [[ $# -gt 0 ]]; do
    case $1 in
      --tasks) need_value "$1" $#; which=$2; shift 2 ;;
      --wait) wait=1; shift ;;
      --parsable) parsable=1; shift ;;
      *) usage "unknown option '$1'" ;;
    esac
  done
  local tasks k
  tasks=$(setting "$dir" tasks)
  if [[ -z $which ]]; then
    for ((k = 0; k < tasks; ++k)); do
      [[ -f $dir/slurm/task-$k.done ]] || which+="${which:+,}$k"
    done
    [[ -n $which ]] || { echo "every task of $dir is done: nothing to resubmit"; return 0; }
  fi
  [[ $which =~ ^[0-9]+(,[0-9]+)*$ ]] || usage "--tasks takes task numbers, e.g. 2,5, not '$which'"
  for k in ${which//,/ }; do
    [[ $k -lt $tasks ]] || usage "task $k is not one of the sweep's 0..$((tasks - 1))"
  done
  submit_tasks "$dir" "$which" "$wait" "$parsable"
}

cmd_merge() {
  [[ $# -ge 1 ]] || usage "merge needs the sweep's folder"
  local dir=$1
  shift
  local plots=()
  while [[ $# -gt 0 ]]; do
    case $1 in
      --no-plots) plots=(--no-plots); shift ;;
      *) usage "unknown option '$1'" ;;
    esac
  done
  local tasks vantage k missing="" shards=()
  tasks=$(setting "$dir" tasks)
  vantage=$(setting "$dir" vantage)
  for ((k = 0; k < tasks; ++k)); do
    [[ -f $dir/slurm/task-$k.done ]] || missing+="${missing:+,}$k"
    shards+=("$dir/shard-$k")
  done
  [[ -z $missing ]] ||
    fail "$dir: task(s) $missing not done (see $dir/slurm/task-I.log); once the array has ended: scripts/slurm-sweep.sh resubmit $dir"
  "$vantage" bench merge "${shards[@]}" --out "$dir" "${plots[@]}"
}

[[ $# -ge 1 ]] || usage "give a command: submit, resubmit or merge"
command=$1
shift
case $command in
  submit) cmd_submit "$@" ;;
  resubmit) cmd_resubmit "$@" ;;
  merge) cmd_merge "$@" ;;
  -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
  *) usage "unknown command '$command' (submit, resubmit or merge)" ;;
esac
