#!/usr/bin/env bash
# Soak: run paper-planar-b for 6 simulated hours and report the element-length
# drift (summary.json max_element_drift), the peak memory (max RSS) and the
# wall time. Results are quoted in docs/reliability.md, "Long runs (soak)".
#
#   scripts/soak.sh [TOWSIM_BINARY] [DURATION_S]
#
# Defaults: build/towsim, 21600 s. Outputs go to $SOAK_OUT (default a fresh
# temporary directory, removed at the end unless SOAK_KEEP=1). Exit status: that
# of the run (0 expected), or 1 when the drift or the peak memory is above
# SOAK_MAX_DRIFT (default 1e-6) or SOAK_MAX_RSS_MB (default 200).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN="${1:-build/towsim}"
DURATION="${2:-21600}"
MAX_DRIFT="${SOAK_MAX_DRIFT:-1e-6}"
MAX_RSS_MB="${SOAK_MAX_RSS_MB:-200}"
OUT="${SOAK_OUT:-$(mktemp -d -t towsim-soak.XXXXXX)}"
[[ -x "$BIN" ]] || { echo "soak.sh: $BIN not found (build first)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "soak.sh: /usr/bin/time not found (apt-get install -y time)" >&2; exit 2; }
cleanup() { [[ "${SOAK_KEEP:-0}" == 1 ]] || rm -rf "$OUT"; }
trap cleanup EXIT

echo "soak: paper-planar-b, duration $DURATION s, output every 1 s, into $OUT"
set +e
/usr/bin/time -v -o "$OUT/time.txt" "$BIN" run --example paper-planar-b --set simulation.duration="$DURATION" \
  --set simulation.output_interval=1 --out "$OUT/run" --quiet
rc=$?
set -e
wall=$(sed -n 's/.*Elapsed (wall clock) time.*: //p' "$OUT/time.txt")
rss_kb=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$OUT/time.txt")
python3 - "$OUT/run/summary.json" "$rc" "$wall" "$rss_kb" "$MAX_DRIFT" "$MAX_RSS_MB" <<'PY' && py=0 || py=$?
import json, sys
path, rc, wall, rss_kb, max_drift, max_rss = sys.argv[1:]
s = json.load(open(path))
drift = s["max_element_drift"]
rss_mb = int(rss_kb) / 1024
print(f"status            {s['status']} (exit {rc}) {s['message']}")
print(f"simulated         {s['end_time']} s in {s['steps']} steps, {s['rhs_evaluations']} RHS evaluations, {s['samples']} samples")
print(f"wall time         {wall} (integration {s['wall_seconds']:.1f} s)")
print(f"peak memory       {rss_mb:.1f} MB (max RSS)")
print(f"element drift     {drift:.3e} (max | |P_k - P_k-1| / L - 1 |)")
ex = s["extremes"]
print(f"max tow tension   {ex['max_tow_tension']['value']:.6g} N at t = {ex['max_tow_tension']['time']} s")
ok = s["status"] == "ok" and drift is not None and drift <= float(max_drift) and rss_mb <= float(max_rss)
print("soak: OK" if ok else f"soak: FAILED (limits: drift {max_drift}, RSS {max_rss} MB)")
sys.exit(0 if ok else 1)
PY
[[ $rc -ne 0 ]] && exit "$rc"
exit "$py"
