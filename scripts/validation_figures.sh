#!/usr/bin/env bash
# Regenerate the statics/theory validation figures (docs/figures/validation_*.png)
# from the data the validation tests write (docs/validation.md).
#
#   scripts/validation_figures.sh
#
# Environment: VAL_BUILD (build directory, default build-val), JOBS (build
# parallelism, default 2). Needs gnuplot. The tests that write data run with
# TOWSIM_VALIDATION_DATA=$VAL_BUILD/validation-data; their pass/fail status
# is reported but the figures are drawn either way.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${VAL_BUILD:-build-val}"
JOBS="${JOBS:-2}"
DATA="$BUILD/validation-data"
OUT=docs/figures

command -v gnuplot >/dev/null || { echo "validation_figures.sh: gnuplot not found" >&2; exit 2; }
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DTOWSIM_BUILD_BENCH=OFF >"$BUILD.configure.log" 2>&1 ||
  { cat "$BUILD.configure.log" >&2; exit 1; }
cmake --build "$BUILD" --target validation_tests -j "$JOBS" >"$BUILD.build.log" 2>&1 ||
  { tail -50 "$BUILD.build.log" >&2; exit 1; }

rm -rf "$DATA"
mkdir -p "$DATA" "$OUT"
TOWSIM_VALIDATION_DATA="$DATA" "$BUILD/tests/validation_tests" \
  --gtest_filter='*StaticsPode*:*TheoryHangingChainLimit*:*StaticsSettling*' >"$DATA/tests.log" 2>&1 ||
  echo "validation_figures.sh: some tests failed (see $DATA/tests.log); drawing the figures anyway" >&2

gnuplot <<EOF
set terminal pngcairo size 900,600 font ",11"
set grid

# 1. Chain statics shape vs Pode's continuous curve.
set output "$OUT/validation_pode_shape.png"
set title "Steady tow at 1 m/s, 100 m cable + 50 kg sphere: chain vs continuous cable (Pode)"
set xlabel "x relative to the tow point [m]"
set ylabel "z relative to the tow point [m]"
set size ratio -1
set key bottom right
plot "$DATA/validation_pode_shape.dat" index 0 with lines lw 2 lc rgb "black" title "continuous (Pode, DOPRI5 1e-13)", \
     "" index 1 with linespoints pt 7 ps 1.0 lc rgb "#d62728" title "chain n = 5", \
     "" index 2 with linespoints pt 5 ps 0.8 lc rgb "#ff7f0e" title "chain n = 10", \
     "" index 3 with linespoints pt 9 ps 0.8 lc rgb "#1f77b4" title "chain n = 20"
set size noratio

# 2. Convergence of the chain to the continuous cable (log-log).
set output "$OUT/validation_pode_convergence.png"
set title "Chain statics vs continuous cable: error against the number of elements n"
set logscale xy
set format y "10^{%L}"
set xlabel "number of elements n"
set ylabel "relative error (tow angle: absolute, rad)"
set key bottom left inside font ",9"
set xrange [4:200]
set yrange [1e-7:0.2]
plot "$DATA/validation_pode_heavy_sphere_morison.dat" u 1:2 w lp pt 7 lc rgb "#1f77b4" t "heavy sphere: tow tension", \
     "" u 1:3 w lp pt 5 lc rgb "#1f77b4" dt 2 t "heavy sphere: tow angle", \
     "" u 1:5 w lp pt 9 lc rgb "#1f77b4" dt 3 t "heavy sphere: offset", \
     "$DATA/validation_pode_heavy_sphere_f003_morison.dat" u 1:2 w lp pt 6 lc rgb "#2ca02c" t "heavy sphere f = 0.03: tension", \
     "$DATA/validation_pode_paper52_v05_morison.dat" u 1:2 w lp pt 7 lc rgb "#d62728" t "5.2 cable 0.5 m/s: tension", \
     "" u 1:4 w lp pt 9 lc rgb "#d62728" dt 3 t "5.2 cable 0.5 m/s: depth", \
     "$DATA/validation_pode_heavy_sphere_ideal.dat" u 1:3 w lp pt 4 ps 1.5 lc rgb "#9467bd" t "ideal fluid vs Pode+Munk: angle", \
     "" u 1:7 w lp pt 12 ps 1.5 lc rgb "#9467bd" dt 2 t "ideal fluid vs plain Pode: angle (stalls)", \
     0.2*x**-2 w l lc rgb "black" dt 4 t "slope -2"

# 3. Linearised hanging chain vs continuous chain (Bessel J0).
set output "$OUT/validation_chain_modes.png"
set title "Hanging chain (10 m): linearised n-link chain vs continuous chain, w_k = (j_{0,k}/2) sqrt(g/L)"
set xrange [4:400]
set yrange [*:*]
set key bottom left inside
set ylabel "relative frequency error"
plot "$DATA/validation_chain_modes.dat" u 1:2 w lp pt 7 t "mode 1", \
     "" u 1:3 w lp pt 5 t "mode 2", \
     "" u 1:4 w lp pt 9 t "mode 3", \
     0.03*x**-2 w l lc rgb "black" dt 4 t "slope -2"

# 4. Settling of a run started hanging to the statics configuration.
set output "$OUT/validation_settling.png"
set title "Run from hanging, tow at speed from t = 0: distance to the statics equilibrium"
unset logscale x
set logscale y
set xrange [*:*]
set xlabel "t [s]"
set ylabel "relative distance"
set key top right inside
plot "$DATA/validation_settling_paper-planar-a.dat" u 1:2 w l lw 2 t "5.1 (2 m/s): max |P_k - P_k^{statics}| / L", \
     "" u 1:3 w l lw 2 dt 2 t "5.1: |F_R - F_R^{statics}| / |F_R|", \
     "$DATA/validation_settling_paper-3d-turn.dat" u 1:2 w l lw 2 t "5.2 (1.57 m/s): max |P_k - P_k^{statics}| / L", \
     "" u 1:3 w l lw 2 dt 2 t "5.2: |F_R - F_R^{statics}| / |F_R|"
EOF
ls -1 "$OUT"/validation_*.png
