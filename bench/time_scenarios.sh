#!/usr/bin/env bash
# Time whole scenarios with the built CLI: median wall time of N runs of
#   towsim run (--example NAME | FILE.yaml) --out DIR --quiet [--set ...]
# and the real-time factor = simulated time / wall time (docs/performance.md).
#
# Usage: bench/time_scenarios.sh [-n RUNS] [-b TOWSIM] [-o OUTROOT] [SCENARIO...] [-- EXTRA towsim ARGS]
#   SCENARIO: a built-in example name or a .yaml file. Default: every built-in
#   example (towsim examples) and bench/scenarios/*.yaml.
#   EXTRA args go to every run, e.g. -- --set simulation.time_step=0.05
# Environment: TOWSIM (default build/towsim; or BUILD=DIR for DIR/towsim), RUNS (default 5).
# Prints a Markdown table; the outputs of the last run of each scenario stay
# in OUTROOT/NAME (default a temporary directory, removed at exit unless -o).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
towsim="${TOWSIM:-${BUILD:-$root/build}/towsim}"
runs="${RUNS:-5}"
outroot=""
scenarios=()
extra=()
while (($#)); do
  case "$1" in
    -n) runs="$2"; shift 2 ;;
    -b) towsim="$2"; shift 2 ;;
    -o) outroot="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    *) scenarios+=("$1"); shift ;;
  esac
done

if [[ ! -x "$towsim" ]]; then
  echo "time_scenarios: $towsim not found or not executable (build first, or set TOWSIM / -b)" >&2
  exit 2
fi
command -v jq >/dev/null || { echo "time_scenarios: jq is required (apt-get install -y jq)" >&2; exit 2; }
if [[ -z "$outroot" ]]; then
  outroot="$(mktemp -d)"
  trap 'rm -rf "$outroot"' EXIT
fi
if ((${#scenarios[@]} == 0)); then
  mapfile -t scenarios < <("$towsim" examples | awk '{print $1}')
  for f in "$root"/bench/scenarios/*.yaml; do [[ -e "$f" ]] && scenarios+=("$f"); done
fi

TIMEFORMAT='%3U %3S'  # for the time keyword: user and system CPU seconds

median() { sort -g | awk '{a[NR]=$1} END {if (NR % 2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }
now() { date +%s.%N; }

echo "towsim: $towsim; $runs runs each; extra args: ${extra[*]:-(none)}"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| scenario | simulated [s] | integrator, step | wall median [s] | wall min [s] | CPU median [s] | run-loop wall (summary.json) median [s] | real-time factor: wall (median) | real-time factor: CPU | steps | rhs evaluations | status |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for sc in "${scenarios[@]}"; do
  if [[ "$sc" == *.yaml ]]; then
    name="$(basename "$sc" .yaml)"
    input=("$sc")
  else
    name="$sc"
    input=(--example "$sc")
  fi
  out="$outroot/$name"
  walls=()
  cpus=()
  inner=()
  status="ok"
  for ((i = 0; i < runs; i++)); do
    rm -rf "$out"
    t0="$(now)"
    rc=0
    # bash's time keyword: user and system CPU time of the run, to the millisecond
    { time "$towsim" run "${input[@]}" --out "$out" --quiet "${extra[@]}" 2>"$outroot/.err" || rc=$?; } 2>"$outroot/.cpu"
    if ((rc != 0)); then status="exit $rc"; cat "$outroot/.err" >&2; fi
    t1="$(now)"
    walls+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.6f", b - a}')")
    cpus+=("$(tail -1 "$outroot/.cpu" | awk '{printf "%.3f", $1 + $2}')")
    [[ -f "$out/summary.json" ]] && inner+=("$(jq -r '.wall_seconds' "$out/summary.json")")
  done
  med="$(printf '%s\n' "${walls[@]}" | median)"
  min="$(printf '%s\n' "${walls[@]}" | sort -g | head -1)"
  if [[ -f "$out/summary.json" ]]; then
    s="$out/summary.json"
    sim="$(jq -r '.end_time' "$s")"
    # the method used (summary.json), the step and tolerance as written (absent: the defaults)
    integ="$(jq -r '.scenario.simulation as $c | "\(.integrator), \($c.time_step // 0.01) s" +
      (if .integrator == "rk4" then "" else ", tol \($c.tolerance // "default")" end)' "$s")"
    steps="$(jq -r '.steps' "$s")"
    rhs="$(jq -r '.rhs_evaluations' "$s")"
    [[ "$status" == ok ]] && status="$(jq -r '.status' "$s")"
    imed="$(printf '%s\n' "${inner[@]}" | median)"
    rtf="$(awk -v s="$sim" -v w="$med" 'BEGIN {printf "%.6f", s / w}')"
    if ((${#cpus[@]})); then
      cmed="$(printf '%s\n' "${cpus[@]}" | median)"
      crtf="$(awk -v s="$sim" -v c="$cmed" 'BEGIN {printf "%.0f", (c > 0) ? s / c : 0}')"
    else
      cmed="-"; crtf="-"
    fi
    printf '| %s | %s | %s | %.3f | %.3f | %s | %.3f | %.0f | %s | %s | %s | %s |\n' \
      "$name" "$sim" "$integ" "$med" "$min" "$cmed" "$imed" "$rtf" "$crtf" "$steps" "$rhs" "$status"
  else
    printf '| %s | - | - | %.3f | %.3f | - | - | - | - | - | - | %s (no summary.json) |\n' "$name" "$med" "$min" "$status"
  fi
done
echo
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
