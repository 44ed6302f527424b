#!/usr/bin/env bash
# Writes the two clouds the manifests here describe into OUT_DIR, with the simulator standing in
# for a robot, and copies the manifests beside them:
#   manifest.yaml  both clouds (vantage plan OUT_DIR)
#   west.yaml      the first cloud alone, south.yaml the second alone: the two steps of the
#                  robot's loop (README, "Use it on your own scans")
# Usage: examples/own-scans/make-data.sh OUT_DIR [path/to/vantage]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:?usage: make-data.sh OUT_DIR [path/to/vantage]}
vantage=${2:-$here/../../build/release/apps/vantage/vantage}
[[ -x "$vantage" ]] || { echo "make-data.sh: no vantage binary at $vantage (build first)" >&2; exit 1; }
mkdir -p "$out"
"$vantage" scan --scene tabletop-3 --pose -1.0,0,1.1,0,0,0 --out "$out/west.pcd"
"$vantage" scan --scene tabletop-3 --pose 0,-1.0,1.1,0,0,90 --out "$out/south.pcd"
cp "$here/manifest.yaml" "$here/west.yaml" "$here/south.yaml" "$out/"
