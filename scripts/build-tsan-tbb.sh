#!/usr/bin/env bash
# Builds oneTBB's libtbb with ThreadSanitizer, for the tsan preset (docs/fuzzing.md, "TSan and
# TBB"). Debian's libtbb12 is not instrumented: TSan cannot see the hand-over of a task from the
# thread that spawns it to the worker that runs it, nor the wait for its end, and reports every
# such hand-over as a race. This builds the same version from Debian's own source tarball
# (checked against the SHA-256 in Debian's .dsc) into build/tbb-tsan/lib, which the tsan test
# preset puts first on LD_LIBRARY_PATH; the soname is the same, so no relink is needed.
# Idempotent: quick when the library is there. Needs apt (as root), cmake and g++ (about a minute with
# JOBS=2 parallel compiles, the default).
#
#   scripts/build-tsan-tbb.sh [DEST]     DEST defaults to build/tbb-tsan
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${1:-$root/build/tbb-tsan}"
version=2021.8.0
tarball=onetbb_$version.orig.tar.xz
sha256=7e9111b8bb59c8800bf6d0b06afe7b0891937443d2dae1ee1101c8e2ede6a7ef

installed=$(dpkg-query -W -f '${Version}' libtbb-dev 2>/dev/null || true)
if [[ $installed != $version* ]]; then
  echo "build-tsan-tbb: libtbb-dev is '${installed:-not installed}', not $version: the headers" \
       "our code is built with must match the library; update version and sha256 here" >&2
  exit 1
fi
if [[ -f $dest/lib/libtbb.so.12 && "$(cat "$dest/lib/.complete" 2>/dev/null)" == "$version" ]]; then
  echo "$dest/lib"
  exit 0
fi

mkdir -p "$dest"
cd "$dest"
if ! echo "$sha256  $tarball" | sha256sum -c --status 2>/dev/null; then
  # NOTE: Debian's source package through apt, from the archive the system's own packages come
  # from: a private copy of its lists with each deb entry read as deb-src, so the machine's apt
  # configuration is left as it was.
  apt_dir=$(mktemp -d)
  trap 'rm -rf "$apt_dir"' EXIT
  mkdir -p "$apt_dir/lists/partial" "$apt_dir/parts"
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f $f ]] && sed 's/^Types: deb$/Types: deb-src/' "$f" >"$apt_dir/parts/$(basename "$f")"
  done
  [[ -f /etc/apt/sources.list ]] && sed -n 's/^deb /deb-src /p' /etc/apt/sources.list >"$apt_dir/parts/main.list"
  apt_opts=(-o "Dir::Etc::SourceList=/dev/null" -o "Dir::Etc::SourceParts=$apt_dir/parts"
            -o "Dir::State::Lists=$apt_dir/lists" -o "APT::Sandbox::User=root")
  apt-get "${apt_opts[@]}" update -qq
  apt-get "${apt_opts[@]}" source --download-only -qq "onetbb=$installed"
  echo "$sha256  $tarball" | sha256sum -c --status || {
    echo "build-tsan-tbb: $tarball does not match its SHA-256" >&2; exit 1; }
fi
rm -rf src obj lib
mkdir src
tar xJf "$tarball" -C src --strip-components 1
# -O1 -g as the tsan preset; only libtbb (no tbbmalloc: Vantage does not link it, no tests).
cmake -S src -B obj -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
      -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBBMALLOC_BUILD=OFF \
      -DTBB_STRICT=OFF >/dev/null
# NOTE: GCC warns that TSan does not model TBB's standalone atomic_thread_fence (-Wtsan); the
# warnings go to obj/build.log, shown only when the build fails.
cmake --build obj --target tbb -j "${JOBS:-2}" >obj/build.log 2>&1 || {
  tail -40 obj/build.log >&2; echo "build-tsan-tbb: the build failed ($dest/obj/build.log)" >&2; exit 1; }
mkdir lib
cp -P obj/*/libtbb.so* lib/
echo "$version" >lib/.complete
echo "$dest/lib"
