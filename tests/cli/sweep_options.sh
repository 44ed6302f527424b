#!/usr/bin/env bash
# issue 50: every option of a sweep is accounted for in what makes its rows reproducible. An option
# either shapes a row, and sweep.json records it (trial_settings and sweep_settings in
# vantage/experiment/bench.cpp) or the trial's key names it (scene, method, a, objective, start),
# or it changes no row and is kept out, so that shards and reruns on other machines share one
# sweep.json. A new option fails here until it is placed in one list or the other.
# Usage: sweep_options.sh VANTAGE
set -euo pipefail
vantage=$1
# In sweep.json or in the trial's key.
shaping=(--scenes --methods --alphas --objectives --trials --scans --seed --revisit --greedy-reference
         --generated
         --objects --generated-seed --candidates --arm-base --reach --view-spacing
         --hemisphere-radii --coverage-tolerance --no-stop-projection --evaluation --search
         --epsilon --lambda --horizon --travel-weight --sample --swept-rays --shortlist
         --integration --no-icp --no-segmentation --no-hole-filling --views --view-radius
         --object-radius --starts)
# Results identical whatever they say (a budget refuses, it never changes a decision).
rowless=(--help --jobs --shard --out --no-plots --max-memory --max-work --max-setup --threads)
for kind in tabletop objects office; do
  while read -r option; do
    [[ " ${shaping[*]} ${rowless[*]} " == *" $option "* ]] || {
      echo "FAIL: bench $kind $option is new: record it in sweep.json (vantage/experiment/bench.cpp," \
        "trial_settings) if it can change a row, and list it in tests/cli/sweep_options.sh" >&2
      exit 1
    }
  done < <("$vantage" bench "$kind" --help | grep -oE '^  (-[a-z],)?--[a-z-]+' | sed 's/.*,//; s/^ *//')
done
echo "ok: every option of bench tabletop, objects and office is accounted for"
