"""Shared helpers of the Python tests (run by ctest with PYTHONPATH=build/python,
TOWSIM_EXE = the built program, TOWSIM_SOURCE_DIR = the source tree)."""
import csv
import math
import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TOWSIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
EXE = os.environ.get("TOWSIM_EXE", str(SOURCE / "build" / "towsim"))
SCENARIOS = SOURCE / "scenarios"

# A short, stiff cable integrated by RK4 beyond its stability limit: blows up
# at about t = 0.24 s (the scenario of tests/unit/test_failure.cpp).
UNSTABLE = """name: unstable
cable: {length: 1, elements: 10, mass_per_length: 0.1, diameter: 0.01}
body:
  mass: 2
  inertia: [0.01, 0.02, 0.02]
  link_point: [0, 0, 0]
  spheres: [{center: [0, 0, 0], radius: 0.05}]
tow:
  motion: [{type: ramp, direction: [1, 0, 0], speed: 3, ramp_time: 0.5}]
simulation: {duration: 2, time_step: 0.01, integrator: rk4, output_interval: 0.1}
"""


def towsim_cli(*args, cwd=None):
    """Run the built program; (exit status, stdout, stderr)."""
    p = subprocess.run([EXE, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=120)
    return p.returncode, p.stdout, p.stderr


def read_csv(path):
    """(header, rows of strings)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def printed(v):
    """A number as the output files print it (12 significant digits), read back."""
    return float(f"{float(v):.12g}")


def same_printed(value, text):
    """True when `value` printed with 12 significant digits reads as the CSV's `text`."""
    if text in ("", "nan", "-nan"):
        return math.isnan(value)
    return printed(value) == float(text)


@pytest.fixture
def towsim_exe():
    return EXE
