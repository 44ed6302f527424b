#!/usr/bin/env bash
# A one-node Slurm on this host for the tests: munged, slurmctld and slurmd as root, with their own
# configuration, state, pid and log files under one folder (spool and sockets in a short one under
# /tmp), on free ports, so it neither needs nor touches a Slurm the machine may run. Sourced, it
# gives two functions:
#   local_slurm_start DIR   starts the daemons, exports SLURM_CONF, waits for the node to be idle;
#                           returns non-zero, naming the daemon and its log's last lines, when
#                           Slurm cannot start
#   local_slurm_stop        stops the daemons it started, by their process ids
# Needs Debian's slurm-wlm and munge (scripts/install-deps.sh) and root, as CI runs.

local_slurm_pids=()
local_slurm_socket_dir=""

local_slurm_fail() {
  echo "local-slurm: $1" >&2
  [[ -n ${2:-} && -f $2 ]] && tail -n 5 "$2" | sed 's/^/  | /' >&2
  return 1
}

# A TCP port nothing listens on now.
local_slurm_free_port() {
  /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# Runs "$@" until it succeeds, every 0.2 s, for at most $1 tries (the daemons' start-up: a poll
# with a bound, not a timed wait).
local_slurm_until() {
  local tries=$1
  shift
  for ((k = 0; k < tries; ++k)); do
    "$@" >/dev/null 2>&1 && return 0
    sleep 0.2
  done
  return 1
}

local_slurm_start() {
  local dir=$1
  [[ $(id -u) -eq 0 ]] || { local_slurm_fail "must run as root (slurmd starts jobs as their user)"; return 1; }
  local tool
  for tool in munged mungekey slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
    command -v "$tool" >/dev/null ||
      { local_slurm_fail "$tool not found: install slurm-wlm and munge (scripts/install-deps.sh)"; return 1; }
  done
  mkdir -p "$dir"/{munge,state,log}
  chmod 700 "$dir/munge"
  # NOTE: munge's socket and slurmd's spool (which holds a socket per job step) live in a short
  # folder of their own: a socket's path may not exceed 107 bytes, and DIR may lie deep in a
  # build tree.
  local_slurm_socket_dir=$(mktemp -d /tmp/vantage-slurm.XXXXXX)
  local socket=$local_slurm_socket_dir/munge.socket
  mkdir -p "$local_slurm_socket_dir/spool"

  mungekey --create --keyfile="$dir/munge/munge.key" --force >/dev/null 2>&1 ||
    { local_slurm_fail "mungekey could not write $dir/munge/munge.key"; return 1; }
  chmod 400 "$dir/munge/munge.key"
  # NOTE: --force: munged checks that no folder above its files is writable by others, which a
  # temporary folder under /tmp is.
  munged --foreground --force --key-file="$dir/munge/munge.key" \
    --socket="$socket" --pid-file="$dir/munge/munged.pid" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge/munged.seed" \
    >"$dir/log/munged.out" 2>&1 &
  local_slurm_pids+=($!)
  local_slurm_until 50 test -S "$socket" ||
    { local_slurm_fail "munged did not start" "$dir/log/munged.log"; return 1; }

  # The node as slurmd finds it (CPUs, sockets, cores, threads, memory), named as the host is.
  local node host
  node=$(slurmd -C | head -n 1)
  host=$(hostname -s)
  [[ $node == NodeName=* ]] || { local_slurm_fail "slurmd -C said '$node', not a node"; return 1; }
  cat >"$dir/slurm.conf" <<EOF
# Written by tests/cli/local_slurm.sh: one node, this host, for a test.
ClusterName=vantage-test
SlurmctldHost=$host
SlurmctldPort=$(local_slurm_free_port)
SlurmdPort=$(local_slurm_free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$local_slurm_socket_dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
KillWait=2
MailProg=/bin/true
$node State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$dir/slurm.conf
  slurmctld -D -i -f "$SLURM_CONF" >"$dir/log/slurmctld.out" 2>&1 &
  local_slurm_pids+=($!)
  local_slurm_until 100 scontrol ping ||
    { local_slurm_fail "slurmctld did not answer" "$dir/log/slurmctld.log"; return 1; }
  slurmd -D -f "$SLURM_CONF" >"$dir/log/slurmd.out" 2>&1 &
  local_slurm_pids+=($!)
  # NOTE: the node is idle once slurmd has registered; only then do jobs start.
  local_slurm_until 150 bash -c "sinfo -h -n $host -o %T | grep -qx idle" ||
    { local_slurm_fail "the node did not come up idle: $(sinfo -h -n "$host" -o %T 2>&1)" \
        "$dir/log/slurmd.log"; return 1; }
}

local_slurm_stop() {
  local k jobs
  # NOTE: jobs still running are cancelled first, by id, so that no task outlives its node daemon;
  # the cluster is this one alone (SLURM_CONF), so these are the test's own jobs.
  if [[ ${#local_slurm_pids[@]} -ge 3 ]]; then
    jobs=$(squeue -h -o %A 2>/dev/null | sort -u | tr '\n' ' ')
    if [[ -n ${jobs// /} ]]; then
      # shellcheck disable=SC2086
      scancel $jobs 2>/dev/null || true
      # shellcheck disable=SC2016 # expanded by the inner shell, at each try
      local_slurm_until 100 bash -c '[[ -z $(squeue -h 2>/dev/null) ]]' || true
    fi
  fi
  # The node first, the controller, then munge: each by the id it was started with.
  for ((k = ${#local_slurm_pids[@]} - 1; k >= 0; --k)); do
    kill "${local_slurm_pids[k]}" 2>/dev/null || true
  done
  for ((k = ${#local_slurm_pids[@]} - 1; k >= 0; --k)); do
    wait "${local_slurm_pids[k]}" 2>/dev/null || true
  done
  local_slurm_pids=()
  if [[ -n ${local_slurm_socket_dir:-} ]]; then
    rm -rf "$local_slurm_socket_dir"
    local_slurm_socket_dir=""
  fi
}
