#!/usr/bin/env bash
# Writes the two clouds manifest.yaml describes, with the simulator standing in for a robot.
# Usage: examples/own-scans/make-data.sh [path/to/vantage]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
vantage=${1:-$here/../../build/release/apps/vantage/vantage}
"$vantage" scan --scene tabletop-3 --pose -1.0,0,1.1,0,0,0 --out "$here/west.pcd"
"$vantage" scan --scene tabletop-3 --pose 0,-1.0,1.1,0,0,90 --out "$here/south.pcd"
