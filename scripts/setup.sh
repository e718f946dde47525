#!/usr/bin/env bash
# Install the Debian packages towsim needs to build and test, only if some
# are missing (apt-get through sudo when not root). Debian 12 (bookworm).
set -euo pipefail

packages=(build-essential cmake ccache libeigen3-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev
          libgtest-dev libgmock-dev libbenchmark-dev libboost-dev gnuplot-nox
          chromium                       # chromium: the headless-browser test of towsim report
          python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pandas python3-distributed
          python3-pytest                 # python3-*: the Python module and its tests
          zlib1g-dev)                    # zlib: the tests that read rendered PNG figures
# ccache: scripts/compiler-cache.sh (builds of unchanged sources are cache hits).
# Node.js and npm bundle the 3-D view of towsim report (npm ci at build time);
# Debian's only when no npm is on PATH (a newer Node.js may be installed already).
if ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi
# --reliability: also what scripts/fuzz.sh and scripts/soak.sh need (clang + libFuzzer, GNU time).
# --lint: also what scripts/tidy.sh and scripts/format.sh need.
for arg in "$@"; do
  case "$arg" in
    --reliability) packages+=(clang libclang-rt-14-dev time) ;;
    --lint) packages+=(clang-tidy clang-format) ;;
    *) echo "setup: unknown option $arg (--reliability, --lint)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}" >&2
sudo=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update
"${sudo[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
