#!/usr/bin/env bash
# Build the libFuzzer targets (scenario, track CSV, sweep file) with clang in
# build-fuzz/ and run each for a bounded time; then fuzz the Python module's
# entry points (fuzz/fuzz_python.py) when build/python holds the module.
# Exit status non-zero when any target crashes, hangs (> 5 s on
# one input), exceeds 2 GB of memory or reports a sanitizer error.
#
#   scripts/fuzz.sh [SECONDS]   fuzz each target for SECONDS (default 60)
#   scripts/fuzz.sh 0           only replay the committed corpus (fuzz/corpus/)
#   FUZZ_RUNS=N FUZZ_SEED=S scripts/fuzz.sh [SECONDS]
#                               N inputs per target from seed S (reproducible:
#                               what CI runs), SECONDS still caps the time
#
# Environment: JOBS (build parallelism, default 2), FUZZ_BUILD (build dir,
# default build-fuzz). New interesting inputs go to $FUZZ_BUILD/corpus/, never
# into the committed seed corpus; crash reproducers to $FUZZ_BUILD/artifacts/.
# Needs clang and libFuzzer (Debian: apt-get install -y clang libclang-rt-14-dev).
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH="${1:-60}"
JOBS="${JOBS:-2}"
BUILD="${FUZZ_BUILD:-build-fuzz}"
CXX_BIN="${FUZZ_CXX:-clang++}"

if ! command -v "$CXX_BIN" >/dev/null; then
  echo "fuzz.sh: $CXX_BIN not found (apt-get install -y clang libclang-rt-14-dev)" >&2
  exit 2
fi

# shellcheck source=scripts/compiler-cache.sh
source scripts/compiler-cache.sh
mkdir -p "$BUILD"
# -O2 -g1: line tables for the reports (a sixth less compile time than -g).
cmake -S . -B "$BUILD" -DCMAKE_CXX_COMPILER="$CXX_BIN" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DTOWSIM_FUZZ=ON -DTOWSIM_BUILD_TESTS=OFF -DTOWSIM_BUILD_BENCH=OFF >"$BUILD/configure.log" 2>&1 ||
  { cat "$BUILD/configure.log" >&2; exit 1; }
cmake --build "$BUILD" --target fuzz_scenario fuzz_track_csv fuzz_sweep -j "$JOBS" >"$BUILD/build.log" 2>&1 ||
  { tail -50 "$BUILD/build.log" >&2; exit 1; }

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
mkdir -p "$BUILD/artifacts"
failed=0
for target in scenario track_csv sweep; do
  exe="$BUILD/fuzz/fuzz_$target"
  seeds="fuzz/corpus/$target"
  work="$BUILD/corpus/$target"
  log="$BUILD/fuzz_$target.log"
  mkdir -p "$work"
  args=(-timeout=5 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1
        "-artifact_prefix=$BUILD/artifacts/${target}-")
  [[ -f fuzz/$target.dict ]] && args+=("-dict=fuzz/$target.dict")
  if [[ "$SECONDS_EACH" == 0 ]]; then
    echo "== fuzz_$target: replaying $seeds"
    "$exe" "${args[@]}" -runs=0 "$seeds" >"$log" 2>&1 && rc=0 || rc=$?
  else
    extra=()
    [[ -n "${FUZZ_RUNS:-}" ]] && extra+=("-runs=$FUZZ_RUNS")
    [[ -n "${FUZZ_SEED:-}" ]] && extra+=("-seed=$FUZZ_SEED")
    echo "== fuzz_$target: ${SECONDS_EACH} s at most${FUZZ_RUNS:+, $FUZZ_RUNS inputs}${FUZZ_SEED:+, seed $FUZZ_SEED}"
    "$exe" "${args[@]}" "${extra[@]}" -max_total_time="$SECONDS_EACH" "$work" "$seeds" >"$log" 2>&1 && rc=0 || rc=$?
  fi
  grep -E '^(stat::number_of_executed_units|stat::peak_rss_mb|#[0-9]+[[:space:]]+DONE)' "$log" || true
  if [[ $rc -ne 0 ]]; then
    echo "fuzz_$target FAILED (exit $rc); log: $log" >&2
    grep -E 'ERROR|SUMMARY|runtime error|Test unit written' "$log" >&2 || tail -30 "$log" >&2
    failed=1
  fi
done
# The Python entry points (towsim.run, statics, sweep), in the module that
# scripts/test.sh built (build/python; PYTHON_BUILD to change it).
pybuild="${PYTHON_BUILD:-build/python}"
if [[ -d "$pybuild/towsim" ]]; then
  # A fixed count (FUZZ_PY_RUNS, default 10000: 6 s here) rather than a
  # time, so that a run from one seed is the same inputs on every machine.
  if [[ "$SECONDS_EACH" == 0 ]]; then pyruns=200; else pyruns="${FUZZ_PY_RUNS:-10000}"; fi
  echo "== fuzz_python: $pyruns inputs, seed ${FUZZ_SEED:-1}"
  PYTHONPATH="$pybuild" /usr/bin/python3 fuzz/fuzz_python.py --runs "$pyruns" --seed "${FUZZ_SEED:-1}" --seconds 600 \
    --repro "$BUILD/artifacts/python-finding.txt" || { echo "fuzz_python FAILED (exit $?)" >&2; failed=1; }
else
  echo "== fuzz_python: skipped ($pybuild/towsim not built: run scripts/test.sh first)"
fi
if [[ $failed -ne 0 ]]; then
  echo "fuzz.sh: FAILED (reproducers in $BUILD/artifacts/)" >&2
  exit 1
fi
echo "fuzz.sh: no crash"
