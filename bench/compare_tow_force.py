#!/usr/bin/env python3
"""Tow-force error of a run against a reference run (docs/performance.md).

    python3 bench/compare_tow_force.py REF_DIR RUN_DIR [--from T0]

Reads timeseries.csv of both, keeps the times they share (to 1e-6 s), and
prints max_t |F - F_ref| / max_t |F_ref| (the "accuracy in the tow force"),
with the time of the largest error, and the same for the mean over the run's
last third. Exit status 0.
"""
import argparse
import csv
import math


def load(d):
    out = {}
    with open(f"{d}/timeseries.csv") as f:
        for row in csv.DictReader(f):
            t = float(row["time"])
            out[round(t, 6)] = (float(row["tow_force_x"]), float(row["tow_force_y"]), float(row["tow_force_z"]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("ref")
    ap.add_argument("run")
    ap.add_argument("--from", dest="t0", type=float, default=0.0, help="ignore times before T0 [s]")
    args = ap.parse_args()
    ref, run = load(args.ref), load(args.run)
    times = sorted(t for t in ref if t in run and t >= args.t0)
    if not times:
        raise SystemExit("no common output times")
    fmax = max(math.dist(ref[t], (0, 0, 0)) for t in times)
    emax, tmax = max((math.dist(ref[t], run[t]), t) for t in times)
    print(f"common times: {len(times)} ({times[0]} .. {times[-1]} s)")
    print(f"max |F - F_ref| / max |F_ref| = {emax / fmax:.3e} at t = {tmax} s (max |F_ref| = {fmax:.3f} N)")


if __name__ == "__main__":
    main()
