#!/usr/bin/env bash
# issue 38, through the command line: the recordings tests/data/make_recordings.py and
# make_mcap.js made (RECORDINGS) plan from a ROS 1 bag, an MCAP file and a TUM RGB-D folder with
# the same map.ot as from the PCD manifest of the same frames; --topic and --every choose frames;
# a TUM folder without ground truth plans as a sequence without poses.
# Usage: plan_recordings.sh VANTAGE RECORDINGS WORK_DIR
set -euo pipefail
vantage=$1
rec=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
plan() { "$vantage" plan --threads 2 --no-plots --top 1 "$@"; }

plan "$rec/pcd.yaml" --out "$work/pcd" >/dev/null
for manifest in bag mcap tum; do
  plan "$rec/$manifest.yaml" --out "$work/$manifest" >"$work/$manifest.txt"
  cmp "$work/$manifest/map.ot" "$work/pcd/map.ot" || fail "$manifest.yaml's map.ot differs from the PCDs'"
done
grep -q "^cloud 3/3  kinect.bag@1305031102.243211 " "$work/bag.txt" || fail "bag frames unnamed: $(head -3 "$work/bag.txt")"
plan "$rec/bag.yaml" --topic /camera/depth/points --every 2 --out "$work/every" >"$work/every.txt"
grep -q "^cloud 2/2 " "$work/every.txt" || fail "--every 2 did not take 2 of 3 frames"

mkdir -p "$work/unposed"
cp -r "$rec/tum" "$rec/tum.yaml" "$work/unposed/"
rm "$work/unposed/tum/groundtruth.txt"
plan "$work/unposed/tum.yaml" --out "$work/unposed_out" >"$work/unposed.txt"
[[ $(grep -c "(pose from registration to the map so far)" "$work/unposed.txt") -eq 2 ]] ||
  fail "the frames after the first were not placed by registration: $(cat "$work/unposed.txt")"
echo "ok"
