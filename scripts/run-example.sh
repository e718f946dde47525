#!/usr/bin/env bash
# Install what is missing, build towsim, and run the default example
# (paper 5.2, a 300 m cable towing a sphere through a turn) into out/paper-3d-turn.
# Builds the program only (target towsim): the tests, benchmarks and the
# Python module are built by scripts/test.sh (or `cmake --build build`).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
# shellcheck source=scripts/compiler-cache.sh
source scripts/compiler-cache.sh
cmake -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2 --target towsim
build/towsim run --example paper-3d-turn --out out/paper-3d-turn
echo "outputs: out/paper-3d-turn/{timeseries.csv,nodes.csv,summary.json}"
