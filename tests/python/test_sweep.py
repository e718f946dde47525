"""`towsim sweep` and towsim.sweep (issue 16): rows equal individual runs,
failing cases are rows, bad sweep files are refused with exact messages."""
import json
import math
import os
import signal
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import towsim
from conftest import EXE, SCENARIOS, UNSTABLE, printed, read_csv, same_printed, towsim_cli

CABLE = SCENARIOS / "cable-tow.yaml"
COMMON = {"simulation.duration": 3, "simulation.write_nodes": False}
GRID = {"tow.motion.0.speed": [1.0, 2.5], "cable.elements": [3, 4]}


def write_sweep(tmp_path, text, name="sweep.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def grid_sweep(tmp_path, extra=""):
    return write_sweep(tmp_path, f"""scenario: {CABLE}
set: {{simulation.duration: 3, simulation.write_nodes: false}}
grid:
  tow.motion.0.speed: [1.0, 2.5]
  cable.elements: [3, 4]
{extra}""")


def cli_table(tmp_path, sweep_file, *args):
    status, out, err = towsim_cli("sweep", sweep_file, "--out", tmp_path / "out", *args)
    assert status == 0, err
    return read_csv(tmp_path / "out" / "sweep.csv")


def test_cli_sweep_rows_equal_individual_runs(tmp_path):
    header, rows = cli_table(tmp_path, grid_sweep(tmp_path, "write_cases: true\n"), "--jobs", "2", "--quiet")
    assert header[:5] == ["case", "tow.motion.0.speed", "cable.elements", "status", "message"]
    # The grid in order, the last key varying fastest.
    assert [r[1:3] for r in rows] == [["1.0", "3"], ["1.0", "4"], ["2.5", "3"], ["2.5", "4"]]
    for i, row in enumerate(rows):
        assert row[0] == str(i) and row[3] == "ok" and row[4] == ""
        overrides = {"tow.motion.0.speed": float(row[1]), "cable.elements": int(row[2]), **COMMON}
        figures = towsim.run(CABLE, overrides).figures
        # The key results a towing table needs are there.
        for name in ("max_tow_tension", "max_end_depth", "final_end_depth", "final_tow_tension"):
            assert name in header
        for name, text in zip(header[5:], row[5:]):
            assert same_printed(figures[name], text), (i, name)
        # Each case's files as `towsim run` writes them.
        summary = json.loads((tmp_path / "out" / f"case-{i:04d}" / "summary.json").read_text())
        assert summary["extremes"]["max_tow_tension"]["value"] == figures["max_tow_tension"]
        assert (tmp_path / "out" / f"case-{i:04d}" / "timeseries.csv").exists()


def test_python_sweep_equals_the_cli_sweep(tmp_path):
    header, rows = cli_table(tmp_path, grid_sweep(tmp_path), "--jobs", "1", "--quiet")
    cases = towsim.grid(str(CABLE), GRID, fixed=COMMON)
    for executor in (None, ThreadPoolExecutor(max_workers=2)):
        table = towsim.sweep(cases, executor, max_workers=2)
        assert list(table["status"]) == ["ok"] * 4
        assert list(table["tow.motion.0.speed"]) == [1.0, 1.0, 2.5, 2.5]
        assert list(table["cable.elements"]) == [3, 4, 3, 4]
        for name in header[5:]:
            for i, row in enumerate(rows):
                assert same_printed(table[name][i], row[header.index(name)]), (name, i)
    dict_table = towsim.sweep(cases[:1], max_workers=1, frame=False)
    assert isinstance(dict_table, dict) and isinstance(dict_table["max_tow_tension"], np.ndarray)


def test_a_failing_case_is_a_row(tmp_path):
    unstable = tmp_path / "unstable.yaml"
    unstable.write_text(UNSTABLE)
    cases = [(str(CABLE), COMMON), (str(unstable), {}), (str(CABLE), {**COMMON, "cable.elements": -2})]
    table = towsim.sweep(cases, max_workers=2)
    assert list(table["status"]) == ["ok", "failed", "invalid"]
    assert table["message"][1].startswith("numerical failure at t = ")
    assert table["message"][2] == "--set:3:16: cable.elements: must be >= 1 (got -2)"
    assert math.isnan(table["max_tow_tension"][2]) and table["max_tow_tension"][1] > 0
    # The same from the command line: the failing case does not stop the others.
    sweep = write_sweep(tmp_path, f"""scenario: {unstable}
cases:
  - {{simulation.time_step: 0.01}}
  - {{simulation.time_step: 0.0005, simulation.duration: 0.5}}
""")
    status, out, err = towsim_cli("sweep", sweep, "--out", tmp_path / "out", "--jobs", "2")
    assert status == 0, err
    header, rows = read_csv(tmp_path / "out" / "sweep.csv")
    assert [r[header.index("status")] for r in rows] == ["failed", "ok"]
    assert rows[0][header.index("message")].startswith("numerical failure at t = ")
    assert "1 ok, 1 failed" in out
    assert "[2/2]" in err  # progress over cases


def test_grid_and_list_combine(tmp_path):
    sweep = write_sweep(tmp_path, f"""example: cable-tow
set: {{simulation.duration: 1, simulation.write_nodes: false}}
grid: {{cable.elements: [2, 3]}}
cases:
  - {{tow.motion.0.speed: 1}}
  - {{tow.motion.0.speed: 2, environment.current: [0.5, 0, 0]}}
""")
    header, rows = cli_table(tmp_path, sweep, "--quiet")
    assert header[:6] == ["case", "cable.elements", "tow.motion.0.speed", "environment.current", "status", "message"]
    # Every list entry with every grid point; the current's value keeps its YAML text.
    assert [r[1:4] for r in rows] == [["2", "1", ""], ["3", "1", ""], ["2", "2", "[0.5, 0, 0]"],
                                      ["3", "2", "[0.5, 0, 0]"]]


BAD_SWEEPS = [
    ("unknown key", "scenario: {cable}\ngrid: {{cable.elements: [2]}}\njobs: 2\n",
     "{f}:3:1: jobs: unknown key (expected one of: scenario, example, set, write_cases, statics, grid, cases)\n"),
    ("typo", "scenario: {cable}\ngird: {{cable.elements: [2]}}\n",
     "{f}:1:1: grid: missing: give the values to sweep (grid: {{KEY: [values]}} and/or cases: [{{KEY: VALUE}}])\n"
     "{f}:2:1: gird: unknown key (did you mean 'grid'?)\n"),
    ("no scenario", "grid: {{cable.elements: [2]}}\n",
     "{f}:1:1: scenario: missing: give the base scenario (scenario: FILE) or a built-in one (example: NAME)\n"),
    ("grid not a list", "example: cable-tow\ngrid:\n  cable.elements: 3\n",
     "{f}:3:19: grid.cable.elements: expected a non-empty list of values (got '3')\n"),
    ("bad key", "example: cable-tow\ncases:\n  - {{cable..length: 3}}\n",
     "{f}:3:6: cases.0.cable..length: not a dotted key path (e.g. cable.length or body.spheres.0.radius)\n"),
    ("both", "example: cable-tow\ngrid: {{cable.elements: [2]}}\ncases:\n  - {{cable.elements: 3}}\n",
     "{f}:4:22: cases.0.cable.elements: also varied by grid\n"),
    ("bad value", "example: cable-tow\ngrid:\n  cable.elements: [2, -1, 0]\n",
     "{f}:3:23: cable.elements: must be >= 1 (got -1)\n{f}:3:27: cable.elements: must be >= 1 (got 0)\n"),
    ("unknown example", "example: cable-tw\ngrid: {{cable.elements: [2]}}\n",
     "{f}:1:10: example: unknown example (did you mean 'cable-tow'?); `towsim examples` lists them\n"),
    ("unknown scenario key", "example: cable-tow\nset: {{cable.lenght: 3}}\ngrid: {{cable.elements: [2]}}\n",
     "{f}:2:21: cable.lenght: unknown key (did you mean 'length'?)\n"),
]


@pytest.mark.parametrize("name,text,expected", BAD_SWEEPS, ids=[b[0] for b in BAD_SWEEPS])
def test_bad_sweep_files_are_refused_with_exact_messages(tmp_path, name, text, expected):
    sweep = write_sweep(tmp_path, text.format(cable=CABLE))
    status, out, err = towsim_cli("sweep", sweep, "--out", tmp_path / "out")
    assert status == 2
    assert err == expected.format(f=sweep)
    assert not (tmp_path / "out").exists()  # nothing written


def test_sigint_keeps_the_rows_so_far(tmp_path):
    sweep = write_sweep(tmp_path, f"""example: paper-3d-turn
set: {{simulation.duration: 100000, simulation.write_nodes: false}}
grid: {{cable.elements: [4, 5, 6, 7]}}
""")
    p = subprocess.Popen([EXE, "sweep", str(sweep), "--out", str(tmp_path / "out"), "--jobs", "2"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    csv_path = tmp_path / "out" / "sweep.csv"
    deadline = time.monotonic() + 30
    while not csv_path.exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(0.3)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    header, rows = read_csv(csv_path)
    statuses = [r[header.index("status")] for r in rows]
    assert len(rows) == 4
    assert statuses.count("interrupted") == 2 and statuses.count("not_run") == 2, statuses
    assert "interrupted after" in err


def test_the_towing_table_example(tmp_path):
    # examples/towing-table.sweep.yaml (docs/python.md): 5 speeds x 4 cable
    # lengths, all steady. Physically: the body goes deeper with more cable
    # and shallower with more speed (drag grows, weight does not).
    header, rows = cli_table(tmp_path, SCENARIOS.parent / "examples" / "towing-table.sweep.yaml", "--quiet")
    assert len(rows) == 20 and all(r[header.index("status")] == "ok" for r in rows)
    depth = {(float(r[1]), float(r[2])): float(r[header.index("final_body_depth")]) for r in rows}
    speeds = sorted({s for s, _ in depth})
    lengths = sorted({L for _, L in depth})
    for s in speeds:
        assert all(depth[s, a] < depth[s, b] for a, b in zip(lengths, lengths[1:])), s
    for L in lengths:
        assert all(depth[a, L] > depth[b, L] for a, b in zip(speeds, speeds[1:])), L


def test_an_error_a_case_causes_points_at_its_override(tmp_path):
    # paper-3d-turn's turn needs speed: the case that takes it away is named.
    sweep = write_sweep(tmp_path, "example: paper-3d-turn\ncases:\n  - {cable.elements: 4}\n  - {tow.motion.0.speed: 0}\n")
    status, out, err = towsim_cli("sweep", sweep, "--out", tmp_path / "out")
    assert status == 2 and out == "" and not (tmp_path / "out").exists()
    assert err == (f"{sweep}:4:26: tow.motion.1: a turn needs a non-zero horizontal tow speed at its start time "
                   "(got 0 m/s at t = 15 s) [caused by --set tow.motion.0.speed=0; see paper-3d-turn.yaml:33:7]\n")
