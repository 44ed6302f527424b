#!/usr/bin/env bash
# issue 38, through the command line: the recordings tests/data/make_recordings.py and
# make_mcap.js made (RECORDINGS) plan from a ROS 1 bag, an MCAP file and a TUM RGB-D folder with
# the same map.ot as from the PCD manifest of the same frames; --topic and --every choose frames;
# a TUM folder without ground truth plans as a sequence without poses; a recording alone plans
# without a manifest (issue 53).
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
# issue 53: a recording alone, without a manifest, maps cell for cell as the manifest that names it
# with the same region, resolution and sensor (CameraInfo's intrinsics, the points' range).
roi="roi: {min: [-0.4, -0.4, 0.7], max: [0.4, 0.4, 1.1]}"
for ext in bag mcap; do
  plan "$rec/kinect.$ext" --topic /camera/depth/points --roi=-0.4,-0.4,0.7,0.4,0.4,1.1 \
    --resolution 0.01 --out "$work/alone_$ext" >"$work/alone_$ext.txt"
  grep -q "^recording alone: sensor 62.7 x 49.1 deg, 0.5-2.5 m (from CameraInfo, its range the points', frame optical); roi (-0.4, -0.4, 0.7) to (0.4, 0.4, 1.1) m (--roi); resolution 0.01 m (--resolution)" \
    "$work/alone_$ext.txt" || fail "kinect.$ext alone: $(head -1 "$work/alone_$ext.txt")"
  cat >"$work/alone_$ext.yaml" <<EOF
recording: {file: $rec/kinect.$ext, topic: /camera/depth/points}
sensor:
  frame: optical
  intrinsics: {fx: 525.0, fy: 525.0, cx: 319.5, cy: 239.5, width: 640, height: 480}
  min_range: 0.5
  max_range: 2.5
$roi
resolution: 0.01
EOF
  plan "$work/alone_$ext.yaml" --out "$work/alone_manifest_$ext" >/dev/null
  cmp "$work/alone_$ext/map.ot" "$work/alone_manifest_$ext/map.ot" ||
    fail "kinect.$ext alone maps otherwise than its manifest"
done
# Without --roi and --resolution: the frames' extent, and a resolution for the sensor's range.
plan "$rec/kinect.bag" --topic /camera/depth/points --out "$work/alone_derived" >"$work/alone_derived.txt"
grep -q "m (the frames' extent); resolution 0.01 m (for the sensor's range)" "$work/alone_derived.txt" ||
  fail "kinect.bag alone, derived: $(head -1 "$work/alone_derived.txt")"
[[ $(grep -c "^cloud " "$work/alone_derived.txt") -eq 3 ]] || fail "kinect.bag alone did not map 3 clouds"
"$vantage" plan --help >"$work/help.txt"
grep -q "or a recording alone (a ROS 1 bag, an MCAP file) with --topic" "$work/help.txt" ||
  fail "plan --help does not say a recording plans alone"
echo "ok"
