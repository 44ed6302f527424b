#!/usr/bin/env bash
# Renders `vantage view`'s page of a 2-scan exploration in headless Chromium and checks the
# result with check_render.py: the page reports a clean render in its DOM, and the screenshot
# shows a drawn scene with the occupied cells' and the chosen view's colours.
# With a map (MAP.bt) in place of the scene: a building (issue 27). `vantage plan --map` with
# frontier candidates, and the page seen from above twice, whole and with the height cut at
# CUT metres (view.html#cut=CUT&above); check_render.py --building then checks that the cut
# hid the top layers (the roof) the whole view shows.
# Usage: render_test.sh VANTAGE SCENE_YAML OUT_DIR           (exit 77: skipped, no chromium)
#        render_test.sh VANTAGE MAP.bt OUT_DIR CUT           (exit 77: also when MAP is missing)
set -euo pipefail
vantage=$1
scene=$2
out=$3
cut=${4:-}
chromium=${CHROMIUM:-/usr/bin/chromium}
if [[ ! -x "$chromium" ]]; then
  echo "SKIP: no chromium at $chromium (scripts/install-deps.sh installs Debian's chromium)"
  exit 77
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$out"
mkdir -p "$out"
profile="$(mktemp -d)"
trap 'rm -rf "$profile"' EXIT

if [[ -n "$cut" ]]; then
  if [[ ! -f "$scene" ]]; then
    echo "SKIP: no map at $scene (tests/data/real/README.md: where it comes from)"
    exit 77
  fi
  "$vantage" plan --map "$scene" --candidates frontier --method greedy --threads 2 --no-plots \
    --out "$out/run" >/dev/null 2>&1
else
  "$vantage" explore --scene "$scene" --scans 2 --seed 1 --threads 2 --quiet --no-plots \
    --out "$out/run" >/dev/null
fi
"$vantage" view "$out/run" --out "$out/view.html"

# NOTE: no GPU here: WebGL runs on SwiftShader, which Chromium only enables when asked.
# --virtual-time-budget lets the page's module finish (it imports three.js from blob: URLs)
# before the DOM is dumped or the screenshot taken.
# NOTE: 240 s, not 120: on the shared 2-core machine under a load of 6-8, the building's software
# WebGL render ran past 120 s once (the ctest TIMEOUT, 600 s, still bounds the whole test).
browse() {
  rm -rf "$profile"/*
  timeout 240 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --use-angle=swiftshader --enable-unsafe-swiftshader --user-data-dir="$profile" \
    --window-size=1280,800 --hide-scrollbars --virtual-time-budget=30000 "$@" \
    "file://$(realpath "$out/view.html")$fragment" 2>"$out/chromium.log" || {
    echo "FAIL: chromium $1 exited with $? (its log: $out/chromium.log)" >&2
    tail -n 20 "$out/chromium.log" >&2
    exit 1
  }
}
fragment=""
if [[ -n "$cut" ]]; then
  fragment="#above"
  browse --screenshot="$out/whole.png" >/dev/null
  fragment="#cut=$cut&above"
fi
# NOTE: one browse for both, the DOM on stdout: each browse renders the page in software anew.
browse --dump-dom --screenshot="$out/viewer.png" >"$out/dom.html"
if [[ -n "$cut" ]]; then
  /usr/bin/python3 "$here/check_render.py" "$out/dom.html" "$out/viewer.png" "$out/whole.png"
else
  /usr/bin/python3 "$here/check_render.py" "$out/dom.html" "$out/viewer.png"
fi
