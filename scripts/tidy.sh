#!/usr/bin/env bash
# clang-tidy (checks in .clang-tidy) over the physics library's sources:
# src/ but src/scenario and src/output, as in CMakeLists.txt. Uses the compile
# commands of build/ (configured here if missing); every finding is an error.
#   scripts/tidy.sh [FILE...]     default: every physics source
# Environment: CLANG_TIDY (clang-tidy), TIDY_BUILD (build), JOBS (2).
set -euo pipefail
cd "$(dirname "$0")/.."
TIDY="${CLANG_TIDY:-clang-tidy}"
BUILD="${TIDY_BUILD:-build}"
JOBS="${JOBS:-2}"
command -v "$TIDY" >/dev/null || { echo "tidy.sh: $TIDY not found (scripts/setup.sh --lint)" >&2; exit 2; }

if [[ ! -f "$BUILD/compile_commands.json" ]]; then
  cmake -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
files=("$@")
if [[ ${#files[@]} -eq 0 ]]; then
  mapfile -t files < <(find src -name '*.cpp' -not -path 'src/scenario/*' -not -path 'src/output/*' | sort)
fi
echo "tidy.sh: ${#files[@]} files, $JOBS at a time"
# -Wno-unknown-warning-option: the commands are GCC's (e.g. -Wno-restrict);
# -Wno-error: TOWSIM_WERROR's -Werror must not turn clang's own warnings into
# errors here (clang-tidy's --warnings-as-errors decides).
status=0
printf '%s\n' "${files[@]}" |
  xargs -P "$JOBS" -n 1 "$TIDY" -p "$BUILD" --quiet --warnings-as-errors='*' \
    --extra-arg=-Wno-unknown-warning-option --extra-arg=-Wno-error 2>&1 |
  { grep -v -E '^[0-9]+ warnings? generated\.$' || true; } || status=$?
if [[ $status -ne 0 ]]; then
  echo "tidy.sh: FAILED (findings above)" >&2
  exit 1
fi
echo "tidy.sh: no findings"
