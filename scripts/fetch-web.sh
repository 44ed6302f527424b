#!/usr/bin/env bash
# Fetches the JavaScript that `vantage view` inlines into its pages: three.js at a pinned version,
# from the npm registry with `npm pack`, into .cache/web (git-ignored), or VANTAGE_WEB_DIR.
# Idempotent: quiet and quick when the files are present. Nothing in the package is executed:
# `npm pack` only downloads the tarball, and Vantage copies two of its files into each page.
#
#   .cache/web/three/build/three.module.min.js                  (three.js, one ES module)
#   .cache/web/three/examples/jsm/controls/OrbitControls.js     (mouse orbit, pan and zoom)
#   .cache/web/three/LICENSE                                    (MIT)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${VANTAGE_WEB_DIR:-$root/.cache/web}"
# NOTE: 0.170 is the last line whose build/three.module.min.js is one self-contained module;
# from r171 on it imports a second file (three.core.js), which a single page would have to inline
# and link as well. `vantage view` checks the version it finds against this pin.
spec=three@0.170.0
keep=(build/three.module.min.js examples/jsm/controls/OrbitControls.js LICENSE package.json)

name="${spec%@*}"
dir="$dest/$name"
if [[ -f "$dir/.vantage-complete" && "$(cat "$dir/.vantage-complete")" == "$spec" ]]; then
  exit 0
fi
source "$root/scripts/npm-unpack.sh"
npm_unpack fetch-web "$spec" "${keep[@]}"
mkdir -p "$tmp/keep"
for file in "${keep[@]}"; do
  mkdir -p "$tmp/keep/$(dirname "$file")"
  mv "$tmp/package/$file" "$tmp/keep/$file"
done
echo "$spec" >"$tmp/keep/.vantage-complete"
mkdir -p "$dest"
rm -rf "$dir"
mv "$tmp/keep" "$dir"
echo "fetch-web: $spec -> $dir"
