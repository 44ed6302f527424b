#!/usr/bin/env bash
# Fetches the independent MCAP writer the recordings tests make their MCAP file with (issue 38):
# npm's @mcap/core (Foxglove's reference MCAP library) and @foxglove/rosmsg2-serialization (ROS 2
# CDR messages), with their dependencies, at pinned versions, from the npm registry with
# `npm pack`, into .cache/node_modules (git-ignored), or VANTAGE_NODE_DIR. Idempotent. Nothing in
# the packages is run here: `npm pack` only downloads; tests/data/make_mcap.js requires them.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${VANTAGE_NODE_DIR:-$root/.cache/node_modules}"
specs=(@mcap/core@2.2.2 @foxglove/crc@0.0.3 heap-js@2.7.1 tslib@2.8.1
       @foxglove/rosmsg2-serialization@3.1.0 @foxglove/cdr@3.5.0
       @foxglove/message-definition@0.5.0 @foxglove/rostime@1.1.3)
pins="${specs[*]}"
if [[ -f "$dest/.vantage-complete" && "$(cat "$dest/.vantage-complete")" == "$pins" ]]; then
  exit 0
fi
source "$root/scripts/npm-unpack.sh"
mkdir -p "$dest"
for spec in "${specs[@]}"; do
  name="${spec%@*}"
  npm_unpack fetch-mcap-writer "$spec"
  rm -rf "${dest:?}/$name"
  mkdir -p "$(dirname "$dest/$name")"
  mv "$tmp/package" "$dest/$name"
  rm -rf "$tmp"
done
echo "$pins" >"$dest/.vantage-complete"
echo "fetch-mcap-writer: ${specs[*]} -> $dest"
