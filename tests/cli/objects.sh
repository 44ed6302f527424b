#!/usr/bin/env bash
# issue 49: a mesh the project has never seen, by path, under the object protocol's defaults: a
# file Debian's assimp-testmodels ships (written by another tool), explored and benched; each run
# leaves scans.csv with the coverage columns and set_cover.csv with every level's fewest views
# proven.
# Usage: objects.sh VANTAGE WORK_DIR
set -euo pipefail
vantage=$1
work=$2
mesh=/usr/share/assimp/models/OFF/Wuson.off
[[ -f $mesh ]] || { echo "FAIL: $mesh is missing: scripts/install-deps.sh installs assimp-testmodels"; exit 1; }
rm -rf "$work"
mkdir -p "$work"
"$vantage" explore --object "$mesh" --scans 4 --no-plots -q --out "$work/explore" >/dev/null
"$vantage" bench objects --objects "$mesh" --starts 2 --scans 3 --methods greedy,greedy-oracle \
  --no-plots --out "$work/bench" >/dev/null
for dir in "$work/explore" "$work/bench"; do
  header=$(head -1 "$dir/scans.csv")
  for column in surface_coverage raw_surface_coverage travel_m; do
    [[ ",$header," == *",$column,"* ]] || { echo "FAIL: $dir/scans.csv has no $column"; exit 1; }
  done
  levels=$(tail -n +2 "$dir/set_cover.csv" | cut -d, -f4 | sort -u | tr '\n' ' ')
  [[ $levels == "80 90 95 99 full " ]] || { echo "FAIL: $dir/set_cover.csv levels: $levels"; exit 1; }
  if tail -n +2 "$dir/set_cover.csv" | grep -v ",proven," >/dev/null; then
    echo "FAIL: a level of $dir/set_cover.csv is not proven"; exit 1
  fi
done
rows=$(tail -n +2 "$work/bench/set_cover.csv" | wc -l)
[[ $rows -eq 10 ]] || { echo "FAIL: bench's set_cover.csv has $rows rows, expected 2 starts x 5"; exit 1; }
grep -q '"coverage_tolerance_cells": 0' "$work/explore/run.json" ||
  { echo "FAIL: an object's run is not counted at MA-SCVP's tolerance (0 cells)"; exit 1; }
echo "ok: a new mesh explored and benched, every level of its fewest views proven"
