"""Messages and documents that must say what the program does: the warnings'
texts, the winch's energy figures, the README's example table and commands."""
import json
import os
import re
import subprocess
import sys

import pytest

import towsim
from conftest import SOURCE, towsim_cli


def run(tmp_path, *args):
    status, out, err = towsim_cli("run", *args, "--out", tmp_path / "out")
    assert status == 0, err
    return err, json.loads((tmp_path / "out" / "summary.json").read_text())


@pytest.mark.parametrize("nodes", [True, False])
def test_the_compression_warning_says_where_to_look(tmp_path, nodes):
    # paper-planar-b's heave pushes the cable at t = 18.4 s.
    err, summary = run(tmp_path, "--example", "paper-planar-b", "--set", "simulation.duration=20",
                       "--set", f"simulation.write_nodes={'true' if nodes else 'false'}")
    force = summary["extremes"]["min_axial_force"]
    assert force["value"] < 0 and force["time"] == 18.4
    where = ("see axial_force in nodes.csv" if nodes else
             "see min_axial_force in summary.json: nodes.csv was not written, simulation.write_nodes is false")
    assert (f"towsim: warning: the cable was in compression (axial force {force['value']:.10g} N at t = 18.4 s; "
            f"{where}): a real cable would go slack there\n") in err
    assert (tmp_path / "out" / "nodes.csv").exists() == nodes


def test_the_stall_warning_is_the_one_the_docs_quote(tmp_path):
    err, summary = run(tmp_path, "--example", "fish-depth-change", "--set", "initial=hanging",
                       "--set", "simulation.duration=5", "--set", "simulation.write_nodes=false")
    stalls = [w for w in summary["warnings"] if " stalled at " in w]
    assert len(stalls) == 1 and f"towsim: warning: {stalls[0]}\n" in err
    docs = (SOURCE / "docs" / "scenario.md").read_text()
    assert f"`{stalls[0]}`" in docs
    assert "not reported yet" not in docs


def test_the_winch_reports_a_gain_as_a_gain(tmp_path):
    # fish-depth-change: 10 removals on a nearly straight cable; the net change
    # is a small gain (the impulses' work), named so, never a negative loss.
    _, summary = run(tmp_path, "--example", "fish-depth-change", "--set", "simulation.write_nodes=false")
    w = summary["winch"]
    assert w["removals"] == 10
    assert w["energy_lost"] >= 0 and w["energy_gained"] >= 0
    assert w["energy_lost"] == 0 or w["energy_gained"] == 0
    assert w["energy_gained"] > 0  # this run's net: 2.1e-6 J gained
    # Tiny against the cable's and fish's kinetic energy (> 2 kJ at 4 kn).
    assert w["energy_gained"] < 1e-6 * 2000


def test_the_readme_lengths_of_cable_are_the_examples():
    readme = (SOURCE / "README.md").read_text()
    rows = re.findall(r"^\| `([a-z0-9-]+)` \| [^|]*?on ([0-9.]+) m of cable", readme, re.M)
    assert {name for name, _ in rows} >= {"fish-depth-change", "sea-state-tow", "fish-depth-control"}
    for name, length in rows:
        cable = re.search(r"^cable:\n(?:  .*\n)*?  length: ([0-9.]+)", towsim.example(name), re.M)
        assert cable and float(cable.group(1)) == float(length), name


def test_the_readme_python_command_names_the_interpreter_that_works():
    readme = (SOURCE / "README.md").read_text()
    command = re.search(r"^PYTHONPATH=build/python (\S+) -c '(.*)'$", readme, re.M)
    assert command, "the README's import command"
    interpreter, code = command.groups()
    assert interpreter == "/usr/bin/python3"
    if sys.executable != interpreter:  # built with -DPython3_EXECUTABLE=another
        pytest.skip(f"the module is built for {sys.executable}")
    out = subprocess.run([interpreter, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": os.environ["PYTHONPATH"]}).stdout
    assert "'fish-depth-control'" in out
