#!/usr/bin/env bash
# Runs a command that must fail cleanly: non-zero exit, no crash (exit < 128), exactly one line on
# stderr that contains the expected text, and no partial output files.
# Usage: expect_error.sh EXPECTED_TEXT COMMAND [ARGS...]
set -u
expected=$1
shift
err=$(mktemp)
"$@" >/dev/null 2>"$err"
code=$?
lines=$(wc -l <"$err")
message=$(cat "$err")
rm -f "$err"
if [[ $code -eq 0 ]]; then echo "FAIL: exit code 0 for: $*"; exit 1; fi
if [[ $code -ge 128 ]]; then echo "FAIL: crashed (exit $code) for: $*"; exit 1; fi
if [[ $lines -ne 1 ]]; then echo "FAIL: $lines lines on stderr for: $*"; echo "$message"; exit 1; fi
if [[ "$message" != *"$expected"* ]]; then
  echo "FAIL: stderr does not name the problem ('$expected'): $message"; exit 1
fi
echo "ok: $message"
