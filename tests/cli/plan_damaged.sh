#!/usr/bin/env bash
# issue 53, through the command line: the recordings the fixture makes (a bag by python3-rosbag,
# an MCAP file by @mcap/core, RECORDINGS), damaged as a disk or a kill damages them (cut after
# the first chunk, a flipped byte in the second), are refused by `vantage plan` with one line
# naming where and the last whole frame (exit 1, no results folder), and with --salvage mapped
# from their whole frames, the damage said in one warning and recorded in plan.json.
# Usage: plan_damaged.sh VANTAGE RECORDINGS WORK_DIR EXPECT_ERROR
set -euo pipefail
vantage=$1
rec=$2
work=$3
expect=$4
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

# The damage, by the test's own walk over the records (wiki.ros.org/Bags/Format/2.0,
# mcap.dev/spec): each file cut at its second chunk, and one flipped byte in the middle of it.
/usr/bin/python3 - "$rec" "$work" <<'EOF'
import struct, sys
rec, work = sys.argv[1:]

def bag_chunks(b):
    pos, out = 13, []
    while pos < len(b):
        hl, = struct.unpack_from("<I", b, pos)
        header = b[pos + 4:pos + 4 + hl]
        dl, = struct.unpack_from("<I", b, pos + 4 + hl)
        if b"op=\x05" in header:
            out.append((pos, pos + 8 + hl, dl))
        pos += 8 + hl + dl
    return out

def mcap_chunks(b):
    pos, out = 8, []
    while pos + 8 < len(b):
        n, = struct.unpack_from("<Q", b, pos + 1)
        if b[pos] == 6:
            out.append((pos, pos + 9, n))
        pos += 9 + n
    return out

for name, chunks in (("kinect.bag", bag_chunks), ("kinect.mcap", mcap_chunks)):
    b = open(f"{rec}/{name}", "rb").read()
    at, data, size = chunks(b)[1]
    ext = name.split(".")[1]
    open(f"{work}/cut.{ext}", "wb").write(b[:at])
    flipped = bytearray(b)
    flipped[data + size // 2] ^= 1
    open(f"{work}/flipped.{ext}", "wb").write(bytes(flipped))
EOF
for damage in cut flipped; do
  for ext in bag mcap; do
    sed "s|kinect\.$ext|$damage.$ext|" "$rec/$ext.yaml" >"$work/${damage}_$ext.yaml"
  done
done

plan() { "$vantage" plan --threads 2 --no-plots --top 1 "$@"; }
# Refused: where, and the last whole frame. (A bag has no checksum: a flipped byte is found only
# where it breaks the bag's structure or its index, tests/io/recording_damage_test.cpp.)
"$expect" --code 1 --absent "$work/out" \
  "cut.bag: the file ends at byte " "$vantage" plan "$work/cut_bag.yaml" --no-plots --out "$work/out" ||
  fail "the cut bag"
"$expect" --code 1 --absent "$work/out" \
  "the last whole frame before it is frame 1 of /camera/depth/points (stamp 1305031102.175304 s); --salvage maps the frames before it" \
  "$vantage" plan "$work/cut_mcap.yaml" --no-plots --out "$work/out" || fail "the cut MCAP file"
"$expect" --code 1 --absent "$work/out" "fails its CRC" \
  "$vantage" plan "$work/flipped_mcap.yaml" --no-plots --out "$work/out" ||
  fail "the flipped MCAP file"

# Salvaged: one warning line, the frames before the damage mapped, plan.json's salvage.
check_salvage() {  # MANIFEST KEPT DROPPED
  plan "$1" --salvage --out "$work/salvaged" >"$work/salvaged.txt" 2>"$work/salvaged.err" ||
    fail "--salvage refused $1: $(cat "$work/salvaged.err")"
  [[ $(wc -l <"$work/salvaged.err") -eq 1 ]] || fail "not one warning: $(cat "$work/salvaged.err")"
  grep -q "damaged; mapped the $2 whole frame(s) before byte " "$work/salvaged.err" ||
    fail "the warning: $(cat "$work/salvaged.err")"
  [[ $(grep -c "^cloud " "$work/salvaged.txt") -eq $2 ]] || fail "not $2 clouds mapped: $(cat "$work/salvaged.txt")"
  /usr/bin/python3 -c "
import json, sys
s = json.load(open('$work/salvaged/plan.json'))['salvage']
assert s['frames_kept'] == $2 and s['frames_dropped'] == $3 and s['byte'] > 0, s
" || fail "plan.json's salvage for $1"
  rm -rf "$work/salvaged"
}
check_salvage "$work/cut_bag.yaml" 1 None
check_salvage "$work/cut_mcap.yaml" 1 None
check_salvage "$work/flipped_mcap.yaml" 1 2
echo "ok"
