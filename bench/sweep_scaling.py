#!/usr/bin/env python3
"""Sweep scaling (issue 16; docs/performance.md): wall time of one sweep of
N equal-cost cases on 1 worker and on k workers (2 .. cores), for
`towsim sweep --jobs k` (threads) and towsim.sweep with k local processes;
parallel efficiency E_k = T_1 / (k T_k). The load average is printed before
and after: on a loaded machine E_k measures the load, not towsim. The CPU
time the sweep used (its processes' user + system time) is printed too: the
same CPU time on k workers as on 1 means the cases do not slow each other
(no shared locks, no memory-bandwidth contention), whatever the load.

    PYTHONPATH=build/python python3 bench/sweep_scaling.py [--build build] [--cases 64] [--duration 60]
"""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--cases", type=int, default=64)
    ap.add_argument("--duration", type=float, default=60.0, help="simulated seconds per case (paper-3d-turn)")
    ap.add_argument("--repeat", type=int, default=1, help="runs per configuration; the fastest is kept")
    a = ap.parse_args()
    sys.path.insert(0, os.path.join(a.build, "python"))
    import towsim

    cores = os.cpu_count() or 1
    workers = [1] + [k for k in (2, 4, 8, 16) if k <= cores]
    # Equal-cost cases: the default example with 64 tow speeds.
    speeds = [round(1.0 + i / a.cases, 6) for i in range(a.cases)]
    fixed = {"simulation.duration": a.duration, "simulation.write_nodes": False}
    print(f"{a.cases} cases of paper-3d-turn, {a.duration:g} s simulated each; {cores} cores; "
          f"load average {os.getloadavg()[0]:.2f}")
    with tempfile.TemporaryDirectory() as tmp:
        sweep = os.path.join(tmp, "sweep.yaml")
        with open(sweep, "w") as f:
            f.write("example: paper-3d-turn\n")
            f.write(f"set: {{simulation.duration: {a.duration}, simulation.write_nodes: false}}\n")
            f.write(f"grid: {{tow.motion.0.speed: [{', '.join(map(str, speeds))}]}}\n")
        cli, cli_cpu = {}, {}
        for k in workers:
            best = float("inf")
            for _ in range(a.repeat):
                c0 = children_cpu()
                t0 = time.monotonic()
                subprocess.run([os.path.join(a.build, "towsim"), "sweep", sweep, "--out", os.path.join(tmp, f"o{k}"),
                                "--jobs", str(k), "--quiet"], check=True)
                best = min(best, time.monotonic() - t0)
                cli_cpu[k] = children_cpu() - c0
            cli[k] = best
        cases = towsim.grid(towsim.example("paper-3d-turn"), {"tow.motion.0.speed": speeds}, fixed=fixed)
        py, py_cpu = {}, {}
        for k in workers:
            best = float("inf")
            for _ in range(a.repeat):
                c0 = children_cpu()
                t0 = time.monotonic()
                table = towsim.sweep(cases, max_workers=k, frame=False)  # its processes end (are reaped) inside
                best = min(best, time.monotonic() - t0)
                py_cpu[k] = children_cpu() - c0
                assert all(s == "ok" for s in table["status"])
            py[k] = best
    print("| workers | towsim sweep --jobs k: wall [s] | efficiency | CPU [s] "
          "| towsim.sweep, k processes: wall [s] | efficiency | CPU [s] |")
    print("|---|---|---|---|---|---|---|")
    for k in workers:
        print(f"| {k} | {cli[k]:.2f} | {cli[1] / (k * cli[k]):.2f} | {cli_cpu[k]:.2f} "
              f"| {py[k]:.2f} | {py[1] / (k * py[k]):.2f} | {py_cpu[k]:.2f} |")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
