#!/usr/bin/env bash
# `vantage view` on bad input: fails as every command must (tests/cli/expect_error.sh: one line
# naming the problem, non-zero exit, no crash) and leaves no page behind.
# Usage: bad_input.sh EXPECTED_TEXT VANTAGE DIR [ARGS...]
set -u
expected=$1
vantage=$2
dir=$3
shift 3
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
page="$(mktemp -d)/view.html"
trap 'rm -rf "$(dirname "$page")"' EXIT
"$here/../cli/expect_error.sh" "$expected" "$vantage" view "$dir" --out "$page" "$@" || exit 1
if [[ -n "$(ls -A "$(dirname "$page")")" ]]; then
  echo "FAIL: a file was left behind: $(ls -A "$(dirname "$page")")"
  exit 1
fi
