#!/usr/bin/env python3
"""Integrators side by side on one scenario (docs/performance.md, issue 10).

    python3 bench/compare_integrators.py SCENARIO.yaml [--towsim build/towsim]
        [--ref "simulation.time_step=0.003125"] [--case "LABEL:key=v,key=v" ...]
        [--duration T] [--runs N] [--out DIR]

Runs a reference (rk4 at --ref settings) once, then each case N times (median
wall time), all with write_nodes=false. For each case prints steps, RHS
evaluations, median wall time (from summary.json), real-time factor, and the
errors against the reference over the shared output times:
max |F_R - F_R,ref| / max |F_R,ref| (tow force), and the same for the tow
tension and the body depth (or end depth) as max |x - x_ref| / max |x_ref|.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import tempfile


def load(d):
    out = {}
    with open(os.path.join(d, "timeseries.csv")) as f:
        for row in csv.DictReader(f):
            out[round(float(row["time"]), 6)] = row
    return out


def run(towsim, scen, out, sets):
    args = [towsim, "run", scen, "-o", out, "--quiet", "--set", "simulation.write_nodes=false"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=False, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def errors(ref, d):
    ts = [t for t in ref if t in d]
    F = lambda r: (float(r["tow_force_x"]), float(r["tow_force_y"]), float(r["tow_force_z"]))
    fmax = max(math.dist(F(ref[t]), (0, 0, 0)) for t in ts)
    ef = max(math.dist(F(ref[t]), F(d[t])) for t in ts) / fmax
    out = {"tow_force": ef}
    for col in ("tow_tension", "body_depth" if "body_depth" in ref[ts[0]] else "end_depth"):
        sc = max(abs(float(ref[t][col])) for t in ts)
        out[col] = max(abs(float(d[t][col]) - float(ref[t][col])) for t in ts) / sc
    return out, len(ts)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario")
    ap.add_argument("--towsim", default="build/towsim")
    ap.add_argument("--ref", default="simulation.time_step=0.003125", help="comma-separated --set of the rk4 reference")
    ap.add_argument("--case", action="append", default=[], help="LABEL:key=v,key=v")
    ap.add_argument("--duration", type=float)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out")
    a = ap.parse_args()
    root = a.out or tempfile.mkdtemp(prefix="towsim_integrators_")
    common = [f"simulation.duration={a.duration}"] if a.duration else []
    ref_dir = os.path.join(root, "ref")
    run(a.towsim, a.scenario, ref_dir, common + ["simulation.integrator=rk4"] + a.ref.split(","))
    ref = load(ref_dir)
    print(f"reference: rk4 {a.ref}; outputs in {root}")
    print("| case | status | steps | RHS evals | wall [s] (median of %d) | x real time | tow force err | tension err | depth err |" % a.runs)
    print("|---|---|---|---|---|---|---|---|---|")
    for c in a.case:
        label, _, kv = c.partition(":")
        sets = common + [s for s in kv.split(",") if s]
        d = os.path.join(root, label.replace(" ", "_"))
        walls = []
        for _ in range(a.runs):
            s = run(a.towsim, a.scenario, d, sets)
            walls.append(s["wall_seconds"])
        e, n = errors(ref, load(d))
        w = statistics.median(walls)
        keys = list(e)
        print(f"| {label} | {s['status']} | {s['steps']} | {s['rhs_evaluations']} | {w:.3f} | {s['end_time'] / w:.0f} | "
              f"{e['tow_force']:.2e} | {e[keys[1]]:.2e} | {e[keys[2]]:.2e} |")


if __name__ == "__main__":
    main()
