#!/usr/bin/env python3
"""Fitted exponent p of cost ~ n^p from bench_dynamics' JSON output.

Least squares of log(CPU time, or wall with --real) against log(n) over n in [NMIN, NMAX] (default
100..1000), per benchmark family. Usage:

    build/bench/bench_dynamics --benchmark_out=bench.json --benchmark_out_format=json
    python3 bench/fit_exponent.py bench.json [--nmin 100] [--nmax 1000]

Prints a table of time per evaluation vs n and the fitted exponent. Uses the
median aggregate when the run had repetitions, else the single run.
"""
import argparse
import json
import math
from collections import OrderedDict


def load(path, key):
    with open(path) as f:
        data = json.load(f)
    rows = OrderedDict()  # family -> {n: ns}
    have_median = any(b.get("aggregate_name") == "median" for b in data["benchmarks"])
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        if have_median and b.get("run_type") != "aggregate":
            continue
        name = b.get("run_name", b["name"])
        if "_BigO" in name or "_RMS" in name:
            continue
        family, _, arg = name.rpartition("/")
        try:
            n = int(arg)
        except ValueError:
            continue
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
        rows.setdefault(family, {})[n] = b[key] * scale
    return data.get("context", {}), rows


def fit(points):
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(t) for _, t in points]
    m = len(xs)
    mx, my = sum(xs) / m, sum(ys) / m
    sxx = sum((x - mx) ** 2 for x in xs)
    sxy = sum((x - mx) * (y - my) for x, y in zip(xs, ys))
    p = sxy / sxx
    resid = [y - (my + p * (x - mx)) for x, y in zip(xs, ys)]
    return p, math.sqrt(sum(r * r for r in resid) / m)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json")
    ap.add_argument("--nmin", type=int, default=100)
    ap.add_argument("--nmax", type=int, default=1000)
    ap.add_argument("--real", action="store_true", help="use real (wall) time instead of CPU time")
    args = ap.parse_args()
    key = "real_time" if args.real else "cpu_time"
    ctx, rows = load(args.json, key)
    ns = sorted({n for fam in rows.values() for n in fam})
    print(f"time per evaluation [ns] ({key}, median of repetitions if any)")
    print("| family | " + " | ".join(f"n={n}" for n in ns) + f" | exponent {args.nmin}..{args.nmax} |")
    print("|---" * (len(ns) + 2) + "|")
    for fam, pts in rows.items():
        cells = [f"{pts[n]:.0f}" if n in pts else "-" for n in ns]
        sel = sorted((n, t) for n, t in pts.items() if args.nmin <= n <= args.nmax)
        if len(sel) >= 2:
            p, rms = fit(sel)
            ex = f"{p:.3f} (rms log resid {rms:.3f}, {len(sel)} points)"
        else:
            ex = "- (fewer than 2 points in range)"
        print(f"| {fam} | " + " | ".join(cells) + f" | {ex} |")
    print()
    for fam, pts in rows.items():
        cells = [f"{pts[n] / n:.1f}" if n in pts else "-" for n in ns]
        print(f"{fam:28s} ns per element: " + "  ".join(cells))


if __name__ == "__main__":
    main()
