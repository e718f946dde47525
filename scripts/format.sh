#!/usr/bin/env bash
# clang-format with the repository's .clang-format.
#   scripts/format.sh --check [FILE...]  report files that differ from the style
#                                        (exit 1 if any); default: every C++ file
#   scripts/format.sh FILE...            reformat these files in place
# The whole tree follows the style (.ci/run checks it): format what you change.
set -euo pipefail
cd "$(dirname "$0")/.."
CLANG_FORMAT="${CLANG_FORMAT:-clang-format}"
command -v "$CLANG_FORMAT" >/dev/null || { echo "format.sh: $CLANG_FORMAT not found (apt-get install clang-format)" >&2; exit 2; }

check=0
if [[ "${1:-}" == "--check" ]]; then check=1; shift; fi
files=("$@")
if [[ ${#files[@]} -eq 0 ]]; then
  if [[ $check -eq 0 ]]; then
    echo "format.sh: name the files to reformat (or --check for all)" >&2
    exit 2
  fi
  mapfile -t files < <(git ls-files 'src/*.cpp' 'src/*.hpp' 'include/*.hpp' 'app/*.cpp' 'app/*.hpp' \
                                    'tests/*.cpp' 'tests/*.hpp' 'bench/*.cpp' 'bench/*.hpp' 'fuzz/*.cpp')
fi

if [[ $check -eq 0 ]]; then
  "$CLANG_FORMAT" -i --style=file "${files[@]}"
  exit 0
fi
bad=0 lines=0
for f in "${files[@]}"; do
  n=$("$CLANG_FORMAT" --style=file "$f" | diff "$f" - | grep -c '^<' || true)
  if [[ $n -gt 0 ]]; then
    echo "$f: $n lines differ"
    bad=$((bad + 1)) lines=$((lines + n))
  fi
done
echo "format.sh: $bad of ${#files[@]} files differ from .clang-format ($lines lines)"
[[ $bad -eq 0 ]]
