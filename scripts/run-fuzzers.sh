#!/usr/bin/env bash
# Runs each libFuzzer harness of a `fuzz` build for a bounded time over its seed corpus and fails
# when any of them finds something (docs/fuzzing.md). New inputs gather in BUILD_DIR/corpus, never
# in the checked-in seeds; a finding's input is saved as BUILD_DIR/findings/<reader>/crash-*
# (or leak-*, timeout-*, oom-*), with the harness's report in BUILD_DIR/findings/<reader>.log.
# Usage: scripts/run-fuzzers.sh BUILD_DIR SECONDS [READER...]   (default: every reader)
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: run-fuzzers.sh BUILD_DIR SECONDS [READER...]}
seconds=${2:?usage: run-fuzzers.sh BUILD_DIR SECONDS [READER...]}
shift 2
readers=("$@")
[[ ${#readers[@]} -eq 0 ]] && readers=(pcd ply manifest scene octomap depth_png tum rosbag mcap)

# Limits that make a finding of what the readers must never do: 10 s for one input, 2 GiB of
# memory in all and 1 GiB in one allocation (a reader must refuse a count the file cannot hold
# before it allocates for it). UBSan is built to stop at the first report (VANTAGE_FUZZ).
flags=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024
       -print_final_stats=1)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}

failed=()
for reader in "${readers[@]}"; do
  harness=$build/fuzz/fuzz_$reader
  [[ -x $harness ]] || { echo "run-fuzzers: no harness $harness (cmake --build --preset fuzz)" >&2; exit 2; }
  corpus=$build/corpus/$reader
  findings=$build/findings/$reader
  mkdir -p "$corpus" "$findings"
  log=$build/findings/$reader.log
  "$harness" "${flags[@]}" -artifact_prefix="$findings/" "$corpus" "fuzz/corpus/$reader" \
    >"$log" 2>&1
  code=$?
  stats=$(grep -E '^stat::(number_of_executed_units|peak_rss_mb)' "$log" | sed 's/^stat:://' | tr -s ' ' |
          tr '\n' ' ')
  if [[ $code -eq 0 ]]; then
    echo "fuzz $reader: ${seconds} s, no finding ($stats, corpus $(ls "$corpus" | wc -l) inputs)"
  else
    echo "fuzz $reader: FINDING (exit $code), see $log:"
    grep -E 'ERROR:|FINDING|SUMMARY|Test unit written|runtime error' "$log" | head -8 | sed 's/^/  /'
    failed+=("$reader")
  fi
done
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "run-fuzzers: findings in ${failed[*]}" >&2
  exit 1
fi
