#!/usr/bin/env bash
# Runs a command that must fail cleanly: the documented exit code (docs/robustness.md; any non-zero
# one unless --code says which), no crash (exit < 128), exactly one line on stderr that contains
# the expected text, printable and short (no raw bytes echoed), no sanitizer report (ASan, LSan,
# UBSan and TSan exit 1 by default, which is also a refusal's code), and no files left behind.
# Usage: expect_error.sh [--code N] [--absent PATH]... [--fresh PATH]... EXPECTED_TEXT COMMAND...
#   --code 0 checks a run that succeeds with exactly one warning line; --fresh removes a path
#   (the run's output) before the run.
set -u
want_code=""
absent=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --code) want_code=$2; shift 2 ;;
    --absent) absent+=("$2"); shift 2 ;;
    --fresh) rm -rf "$2"; shift 2 ;;
    *) break ;;
  esac
done
expected=$1
shift
for path in "${absent[@]}"; do rm -rf "$path"; done
err=$(mktemp)
"$@" >/dev/null 2>"$err"
code=$?
lines=$(wc -l <"$err")
bytes=$(wc -c <"$err")
message=$(cat "$err")
unprintable=$(LC_ALL=C tr -d '\n\t -~\200-\377' <"$err" | wc -c)
rm -f "$err"
sanitizer=$(grep -m 1 -E '^(==[0-9]+==ERROR: [A-Za-z]+Sanitizer|WARNING: ThreadSanitizer|SUMMARY: [A-Za-z]+Sanitizer)|: runtime error: ' <<<"$message")
if [[ -n $sanitizer ]]; then echo "FAIL: sanitizer report (exit $code) for: $*"; echo "$message"; exit 1; fi
if [[ -z $want_code && $code -eq 0 ]]; then echo "FAIL: exit code 0 for: $*"; exit 1; fi
if [[ $code -ge 128 ]]; then echo "FAIL: crashed (exit $code) for: $*"; exit 1; fi
if [[ -n $want_code && $code -ne $want_code ]]; then
  echo "FAIL: exit code $code, not $want_code, for: $*"; echo "$message"; exit 1
fi
if [[ $lines -ne 1 ]]; then echo "FAIL: $lines lines on stderr for: $*"; echo "$message"; exit 1; fi
if [[ $unprintable -ne 0 || $bytes -gt 600 ]]; then
  echo "FAIL: stderr holds $unprintable control bytes, $bytes bytes in all: $message"; exit 1
fi
if [[ "$message" != *"$expected"* ]]; then
  echo "FAIL: stderr does not name the problem ('$expected'): $message"; exit 1
fi
for path in "${absent[@]}"; do
  if [[ -e $path || -L $path ]]; then echo "FAIL: left $path behind"; exit 1; fi
done
echo "ok (exit $code): $message"
