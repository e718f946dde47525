#!/usr/bin/env bash
# Install what is missing, build towsim, and run the default example
# (paper 5.2, a 300 m cable towing a sphere through a turn) into out/paper-3d-turn.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cmake -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
build/towsim run --example paper-3d-turn --out out/paper-3d-turn
echo "outputs: out/paper-3d-turn/{timeseries.csv,nodes.csv,summary.json}"
