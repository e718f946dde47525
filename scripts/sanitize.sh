#!/usr/bin/env bash
# Build everything with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DTOWSIM_SANITIZE=ON) in build-asan/ and run the test suite under them.
# Any sanitizer report fails the test that triggered it (UBSan does not
# recover; ASan aborts), so a green run means no report.
#
#   scripts/sanitize.sh [extra ctest arguments]
#
# Environment: JOBS (build and test parallelism, default 2), ASAN_BUILD (build
# dir, default build-asan), SANITIZE_EXCLUDE (ctest -E regex of tests left out,
# default: the long tests listed in scripts/sanitize-long-tests.txt, see
# docs/reliability.md), SANITIZE_ALL=1 (leave nothing out), SANITIZE_SKIP (UBSan
# checks left out, default alignment,null,vptr,pointer-overflow; "" for none).
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS="${JOBS:-2}"
BUILD="${ASAN_BUILD:-build-asan}"
# Default: the long tests of scripts/sanitize-long-tests.txt (regex per line,
# '#' comments), joined into one ctest -E regex.
long_tests() { sed -e 's/#.*//' -e 's/[[:space:]]*$//' -e '/^$/d' scripts/sanitize-long-tests.txt | paste -sd'|'; }
if [[ "${SANITIZE_ALL:-0}" == 1 ]]; then
  EXCLUDE=""
else
  EXCLUDE="${SANITIZE_EXCLUDE:-$(long_tests)}"
fi

# shellcheck source=scripts/compiler-cache.sh
source scripts/compiler-cache.sh
mkdir -p "$BUILD"
# The Python module is left out: an ASan-instrumented extension cannot load
# into an uninstrumented interpreter; the main run tests it.
# -O2 -g1: -g1 keeps only the line tables the reports are symbolised from
# (a sixth less compile time than -g). Not -O1: the tests then run 30 to 80
# times slower than in Release, Eigen's expressions left uninlined.
# UBSan without its alignment, null, vptr and pointer-overflow checks (the
# half of the compile time they cost; ASan catches the bad accesses behind
# them, and the fuzz build keeps every check): SANITIZE_SKIP="" keeps them
# (docs/reliability.md "CI time budget").
SKIP="${SANITIZE_SKIP-alignment,null,vptr,pointer-overflow}"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DTOWSIM_SANITIZE=ON -DTOWSIM_SANITIZE_SKIP="$SKIP" -DTOWSIM_BUILD_BENCH=OFF -DTOWSIM_PYTHON=OFF \
  >"$BUILD/configure.log" 2>&1 || { cat "$BUILD/configure.log" >&2; exit 1; }
cmake --build "$BUILD" -j "$JOBS" >"$BUILD/build.log" 2>&1 || { tail -50 "$BUILD/build.log" >&2; exit 1; }

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
args=(--test-dir "$BUILD" --output-on-failure -j "$JOBS")
[[ -n "$EXCLUDE" ]] && args+=(-E "$EXCLUDE")
ctest "${args[@]}" "$@"
