#!/usr/bin/env bash
# Install what is missing, build towsim with its tests, and run every test.
# With CI=true, compiler warnings are errors (-DTOWSIM_WERROR=ON); extra
# CMake arguments can be given in TOWSIM_CMAKE_ARGS (e.g. "-DTOWSIM_BUILD_BENCH=OFF").
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
# shellcheck source=scripts/compiler-cache.sh
source scripts/compiler-cache.sh
werror=OFF
[[ "${CI:-}" == true ]] && werror=ON
# shellcheck disable=SC2086  # TOWSIM_CMAKE_ARGS is a list of arguments
cmake -B build -DCMAKE_BUILD_TYPE=Release -DTOWSIM_WERROR="$werror" ${TOWSIM_CMAKE_ARGS:-}
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2
