#!/usr/bin/env bash
# Installs the Debian packages Vantage builds against. Idempotent: quiet and quick when all
# are present. Usage: scripts/install-deps.sh [core|full|fuzz]   (default: full; fuzz = full and
# clang with libFuzzer and llvm-symbolizer, for `make fuzz` and the fuzz preset)
set -euo pipefail

core=(cmake g++ make pkg-config libeigen3-dev libtbb-dev libgtest-dev libbenchmark-dev
      libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libyaml-cpp-dev
      python3-matplotlib python3-scipy pybind11-dev python3-dev python3-numpy python3-pytest)
# assimp-testmodels: meshes another tool wrote, for the object protocol's test (cli.objects).
# chromium: the test that renders `vantage view`'s page headless (skipped without it).
# zlib1g-dev: the CRC32s of MCAP files (issue 53), named though libpng-dev brings it.
edge=(liboctomap-dev libembree-dev libassimp-dev assimp-testmodels libpcl-dev libnanoflann-dev npm chromium
      libpng-dev libzstd-dev liblz4-dev zlib1g-dev)
# The recordings tests' ROS 1 bag is written by Debian's python3-rosbag (issue 38).
edge+=(python3-rosbag python3-sensor-msgs python3-tf2-msgs)
# cli.slurm_sweep starts a one-node Slurm of its own (tests/cli/local_slurm.sh, issue 50).
edge+=(slurm-wlm munge)

# libclang-rt-dev: libFuzzer and the sanitizer runtimes; llvm: llvm-symbolizer for their reports.
fuzz=(clang libclang-rt-dev llvm)

wanted=("${core[@]}")
case "${1:-full}" in
  core) ;;
  full) wanted+=("${edge[@]}") ;;
  fuzz) wanted+=("${edge[@]}" "${fuzz[@]}") ;;
  *) echo "install-deps: unknown set '$1' (core, full or fuzz)" >&2; exit 2 ;;
esac

missing=()
for pkg in "${wanted[@]}"; do
  # NOTE: a Node.js from elsewhere (NodeSource) brings its own npm and conflicts with Debian's.
  [[ "$pkg" == npm ]] && command -v npm >/dev/null && continue
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$pkg")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
