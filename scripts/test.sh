#!/usr/bin/env bash
# Install what is missing, build towsim with its tests, and run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cmake -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2
