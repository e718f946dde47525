#!/usr/bin/env python3
"""The towing table: body depth and layback for tow speeds of 2-6 knots and
cable lengths of 200-1500 m, made with one towsim.sweep of steady tows (20
`towsim statics` cases on every core), printed as a table, written as CSV and
plotted (gnuplot).

    PYTHONPATH=build/python /usr/bin/python3 examples/towing_table.py [OUT_DIR] [--dask]

--dask runs the cases on a local Dask cluster (2 worker processes) instead of
local processes: the same call with a distributed.Client as the executor.
"""
import os
import shutil
import subprocess
import sys

import towsim

KNOT = 1852.0 / 3600.0  # [m/s]
SPEEDS_KN = [2, 3, 4, 5, 6]
LENGTHS = [200, 500, 1000, 1500]  # [m]
HERE = os.path.dirname(os.path.abspath(__file__))


def table(executor=None):
    cases = towsim.grid(os.path.join(HERE, "towing.yaml"),
                        {"tow.motion.0.speed": [round(kn * KNOT, 4) for kn in SPEEDS_KN], "cable.length": LENGTHS})
    t = towsim.sweep(cases, executor, frame=False, statics=True)  # a dict of arrays: no pandas needed
    # The towing table's columns (depth, layback, tension, top angle, offsets) beside the figures.
    t.update({k: v for k, v in towsim.towing_table(t).items() if k not in t})
    t["speed_kn"] = [round(v / KNOT, 1) for v in t["tow.motion.0.speed"]]
    return t


def main():
    args = [a for a in sys.argv[1:] if a != "--dask"]
    out = args[0] if args else "out/towing-table"
    os.makedirs(out, exist_ok=True)
    if "--dask" in sys.argv:
        from distributed import Client, LocalCluster
        with LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster, \
                Client(cluster) as client:
            t = table(client)
    else:
        t = table()
    bad = [s for s in t["status"] if s != "ok"]
    if bad:
        sys.exit(f"towing_table: {len(bad)} cases did not run: {sorted(set(t['message']))}")

    # The table: one line per cable length, depth / layback per speed.
    print("body depth / layback [m]")
    print("| cable [m] | " + " | ".join(f"{kn} kn" for kn in SPEEDS_KN) + " |")
    print("|---" * (len(SPEEDS_KN) + 1) + "|")
    for length in LENGTHS:
        cells = [f"{d:.0f} / {l:.0f}" for d, l, L in zip(t["final_body_depth"], t["final_layback"], t["cable.length"])
                 if L == length]
        print(f"| {length} | " + " | ".join(cells) + " |")

    csv_path = os.path.join(out, "towing_table.csv")
    with open(csv_path, "w") as f:
        f.write("# speed_kn,cable_length,body_depth,layback,tow_tension,top_angle_deg\n")
        for row in zip(t["speed_kn"], t["cable.length"], t["final_body_depth"], t["final_layback"],
                       t["final_tow_tension"], t["top_angle_deg"]):
            f.write(",".join(f"{v:.6g}" for v in row) + "\n")
    print(f"written: {csv_path}")

    # The plot: depth against layback, one curve per speed, points at the cable lengths.
    if shutil.which("gnuplot") is None:
        print("gnuplot not found: no plot")
        return
    png = os.path.join(out, "towing_table.png")
    plots = ", ".join(f"'{csv_path}' using ($1=={kn} ? $4 : 1/0):3 with linespoints lw 2 title '{kn} kn'"
                      for kn in SPEEDS_KN)
    script = (f"set terminal pngcairo size 800,560 noenhanced; set output '{png}'; set datafile separator ',';"
              "set title 'Towfish depth and layback, cable lengths 200, 500, 1000, 1500 m';"
              "set xlabel 'layback [m]'; set ylabel 'body depth [m]'; set grid; set key bottom left;"
              "set yrange [0:*] reverse;"
              f"plot {plots}")
    subprocess.run(["gnuplot", "-e", script], check=True)
    print(f"written: {png}")


if __name__ == "__main__":
    main()
