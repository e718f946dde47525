#!/usr/bin/env bash
# The cost of an irregular sea (docs/performance.md "Sea states"): the shipped
# sea-state-tow (JONSWAP, 200 harmonics) against the same tow in a regular
# wave of the same height and period, 300 s each at default settings, whole
# process, side by side (N alternated runs, median wall time); then one
# 3-hour storm of sea-state-tow at default settings; with --accuracy, the
# tow tension of the 300 s run against a tight reference run (tolerance 1e-7).
#
# Usage: bench/sea_state_storm.sh [-n RUNS] [-b TOWSIM] [--no-storm] [--accuracy]
# Environment: TOWSIM (default build/towsim). Needs python3.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
towsim="${TOWSIM:-$here/../build/towsim}"
runs=3
storm=1
accuracy=0
while (($#)); do
  case "$1" in
    -n) runs="$2"; shift 2 ;;
    -b) towsim="$2"; shift 2 ;;
    --no-storm) storm=0; shift ;;
    --accuracy) accuracy=1; shift ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "sea_state_storm: unknown argument $1" >&2; exit 2 ;;
  esac
done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The irregular sea as shipped, and the regular wave of its Hs and Tp.
"$towsim" examples sea-state-tow >"$work/irregular.yaml"
sed 's/^  spectrum: {type: jonswap.*/  regular: {height: 3.0, period: 9.0, heading_deg: 180}/' "$work/irregular.yaml" \
  >"$work/regular.yaml"
grep -q "regular:" "$work/regular.yaml" || { echo "sea_state_storm: the example's spectrum line changed" >&2; exit 2; }

summary() {  # DIR -> "steps rejected evaluations run-loop-seconds"
  python3 -c "import json,sys; d=json.load(open(sys.argv[1]+'/summary.json')); \
print(d['steps'], d['rejected_steps'], d['rhs_evaluations'], d['wall_seconds'])" "$1"
}
wall() {  # command... -> wall seconds of the whole process
  local t0 t1
  t0=$(date +%s.%N)
  "$@"
  t1=$(date +%s.%N)
  python3 -c "print(f'{$t1 - $t0:.3f}')"
}

echo "| case | run | wall [s] | steps | rejected | evaluations |"
echo "|---|---|---|---|---|---|"
declare -A walls
for ((r = 1; r <= runs; r++)); do
  for sea in irregular regular; do
    w=$(wall "$towsim" run "$work/$sea.yaml" --out "$work/$sea" --set simulation.duration=300 --quiet)
    read -r steps rej ev _ <<<"$(summary "$work/$sea")"
    echo "| $sea 300 s | $r | $w | $steps | $rej | $ev |"
    walls[$sea]+="$w "
  done
done
python3 - "${walls[irregular]}" "${walls[regular]}" <<'PY'
import statistics, sys
i = statistics.median(map(float, sys.argv[1].split())); r = statistics.median(map(float, sys.argv[2].split()))
print(f"\nmedian wall: irregular {i:.3f} s, regular {r:.3f} s, ratio {i / r:.2f}")
PY

if ((accuracy)); then
  "$towsim" run "$work/irregular.yaml" --out "$work/reference" --set simulation.duration=300 \
    --set simulation.tolerance=1e-7 --set simulation.write_nodes=false --quiet
  python3 - "$work/reference" "$work/irregular" <<'PY'
import csv, sys
def load(d):
    with open(d + "/timeseries.csv") as f:
        return {round(float(r["time"]), 6): float(r["tow_tension"]) for r in csv.DictReader(f)}
ref, run = load(sys.argv[1]), load(sys.argv[2])
ts = sorted(t for t in ref if t in run)
peak = max(abs(ref[t]) for t in ts)
e, te = max((abs(ref[t] - run[t]), t) for t in ts)
print(f"tow tension against tolerance 1e-7: max |T - T_ref| / max T_ref = {e / peak:.3e} at t = {te} s "
      f"over {len(ts)} output times (peak {peak:.1f} N)")
PY
fi

if ((storm)); then
  w=$(wall "$towsim" run "$work/irregular.yaml" --out "$work/storm" --set simulation.duration=10900 --quiet)
  read -r steps rej ev loop <<<"$(summary "$work/storm")"
  echo "3-hour storm (10900 s: 100 s start-up + 10800 s): wall $w s (run loop $loop s), $steps steps, $rej rejected, $ev evaluations"
  python3 -c "import json,sys; d=json.load(open(sys.argv[1]+'/summary.json')); \
s=d['statistics']['tow_tension']; print('tow tension: max', round(s['max'],1), 'mpm', round(s['mpm'],1), \
'max_above_mpm', s['max_above_mpm'], 'skewness', round(s['skewness'],3), 'kurtosis', round(s['kurtosis'],3), \
'weibull shape', s['weibull_shape'] and round(s['weibull_shape'],3), 'weibull_mpm', s['weibull_mpm'] and round(s['weibull_mpm'],1))" "$work/storm"
fi
