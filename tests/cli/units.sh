#!/usr/bin/env bash
# plan.json, run.json and the terminal say the same numbers in the same units for every method
# and objective (issue 27): the survival reading ranks by cells, the paper's method by bits;
# both files record the sensor, plan.json how many clouds it mapped.
# Usage: units.sh VANTAGE DATA_DIR SMALL_SCENE WORK_DIR
set -euo pipefail
vantage=$1
data=$2
scene=$3
work=$4
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

cat >"$work/milk.yaml" <<YAML
clouds: [{file: $data/milk_cartoon_all_small_clorox.pcd}]
sensor: {frame: optical, fov_deg: {horizontal: 60, vertical: 45}, min_range: 0.4, max_range: 3.0}
roi: {min: [-0.4, -0.4, 0.7], max: [0.4, 0.4, 1.1]}
resolution: 0.02
options: {table_segmentation: true, skip_non_finite: true, icp: true}
YAML
check() {  # NAME OBJECTIVE SCORE_UNIT GAIN_UNIT [plan options...]
  local name=$1 objective=$2 score=$3 gain=$4
  shift 4
  "$vantage" plan "$work/milk.yaml" --threads 2 --no-plots --out "$work/$name" "$@" >"$work/$name.txt"
  grep -q "score \[$score\]" "$work/$name.txt" || fail "$name: the table's score is not in $score"
  /usr/bin/python3 - "$work/$name" "$objective" "$score" "$gain" <<'PY'
import json, math, re, sys
folder, objective, score, gain = sys.argv[1:]
plan = json.load(open(f"{folder}/plan.json"))
text = open(f"{folder}.txt").read()
def fail(message):
    sys.exit(f"FAIL: {folder}: {message}")
units = plan["units"]
if (plan["objective"], units["score"], units["predicted_gain"]) != (objective, score, gain):
    fail(f"objective {plan['objective']}, units {units}")
if units["predicted_cells"] != "cells" or units["greedy_gain"] != "cells" or units["travel"] != "m":
    fail(f"units {units}")
best = plan["next_best_view"]
# The terminal's next-best-view line says the score plan.json holds, in its unit.
line = re.search(r"next best view: candidate (\d+) .*score ([0-9.]+) (\S+), decided", text)
if not line or int(line[1]) != best["index"] or line[3] != score \
        or abs(float(line[2]) - best["score"]) > 0.051:
    fail(f"the terminal says {line and line[0]}, plan.json {best['index']} {best['score']} {score}")
want = {"cells": best["predicted_cells"], "bits": best["predicted_gain"]}.get(score)
if plan["method"] == "latombe+surface":
    # The surface a scan adds [cells], discounted by the travel at --lambda's default 0.5 /m.
    want = best["predicted_gain"] * math.exp(-0.5 * best["travel"])
    if not (abs(best["score"] - want) <= 1e-9 * want and best["travel"] > 0):
        fail(f"score {best['score']} is not the surface gain x exp(-0.5 travel) {want}")
elif want is not None and best["score"] != want:
    fail(f"score {best['score']} is not the {score} prediction {want}")
sensor = plan["sensor"]
got = (sensor["horizontal_fov_deg"], sensor["vertical_fov_deg"], sensor["min_range_m"],
       sensor["max_range_m"])
if any(abs(a - b) > 1e-9 for a, b in zip(got, (60, 45, 0.4, 3.0))) or plan["clouds"] != 1:
    fail(f"sensor {sensor}, clouds {plan['clouds']}")
PY
}
check default cells cells cells  # latombe+surface: the surface a scan adds, discounted by travel
grep -q "(latombe+surface method, swept search)" "$work/default.txt" ||
  fail "the default is not latombe+surface: $(grep "next best view" "$work/default.txt")"
check survival cells cells bits --method survival
# A first cloud has nothing to register against: said so, not "ICP kept the pose".
grep -q "(first cloud: nothing to register against)" "$work/survival.txt" ||
  fail "the first cloud's registration: $(head -1 "$work/survival.txt")"
check survival_bits bits bits bits --method survival --objective bits
check probabilistic bits bits bits --method probabilistic
check probabilistic_cells cells cells bits --method probabilistic --objective cells --alpha 0.9
check greedy cells cells cells --method greedy

# explore: run.json says the same; the terminal's lines read plainly.
"$vantage" explore --scene "$scene" --scans 2 --threads 2 --no-plots --out "$work/explore" >"$work/explore.txt"
if grep -q "took all" "$work/explore.txt"; then fail "explore says: $(grep "took all" "$work/explore.txt")"; fi
/usr/bin/python3 - "$work/explore" <<'PY'
import csv, json, sys
folder = sys.argv[1]
run = json.load(open(f"{folder}/run.json"))
# The default around a table top: latombe+surface, in cells.
if run["config"]["method"] != "latombe+surface" or run["objective"] != "cells" \
        or run["units"]["score"] != "cells" or run["units"]["predicted_gain"] != "cells":
    sys.exit(f"FAIL: explore: {run['config']['method']}, objective {run['objective']}, units {run['units']}")
if set(run["sensor"]) != {"horizontal_fov_deg", "vertical_fov_deg", "min_range_m", "max_range_m"}:
    sys.exit(f"FAIL: explore: sensor {run['sensor']}")
rows = list(csv.DictReader(open(f"{folder}/scans.csv")))
first = rows[0]
for key in ("displacement_before_m", "displacement_after_m", "displacement_final_m"):
    if float(first[key]) != 0.0:
        sys.exit(f"FAIL: explore: scan 1 was taken at its true pose, yet {key} = {first[key]}")
PY
echo "ok: units agree"
