"""towsim.run / towsim.statics against the command line's files (issue 16)."""
import _thread
import json
import math
import os
import pathlib
import signal
import threading
import time

import numpy as np
import pytest

import towsim
from conftest import SCENARIOS, UNSTABLE, read_csv, same_printed, towsim_cli

# Short runs: 5 simulated seconds of each example are enough to compare
# every number, and keep the whole file to a few seconds.
SHORT = {"simulation.duration": 5}


def assert_series_match_csv(result, csv_path):
    header, rows = read_csv(csv_path)
    assert header == result.columns
    assert len(rows) == len(result["time"])
    for j, column in enumerate(header):
        values = result[column]
        for i, row in enumerate(rows):
            assert same_printed(values[i], row[j]), (column, i, values[i], row[j])


def assert_nodes_match_csv(result, csv_path):
    header, rows = read_csv(csv_path)
    assert header == ["time", "node"] + result.node_columns
    t, joints, comps = result.nodes.shape
    assert len(rows) == t * joints
    for r, row in enumerate(rows):
        i, k = divmod(r, joints)
        assert int(row[1]) == k
        assert same_printed(result["time"][i], row[0])
        for c in range(comps):
            assert same_printed(result.nodes[i, k, c], row[2 + c]), (i, k, c)


@pytest.mark.parametrize("example", ["paper-3d-turn", "cable-tow"])  # with and without a body
def test_run_equals_the_cli_files(tmp_path, example):
    path = SCENARIOS / f"{example}.yaml"
    status, _, err = towsim_cli("run", path, "--out", tmp_path, "--set", "simulation.duration=5", "--quiet")
    assert status == 0, err
    r = towsim.run(str(path), SHORT)
    assert r.status == "ok"
    # Every number of timeseries.csv and nodes.csv, to the 12 printed digits.
    assert_series_match_csv(r, tmp_path / "timeseries.csv")
    assert_nodes_match_csv(r, tmp_path / "nodes.csv")
    # summary.json: the same document but for the wall-clock time.
    cli = json.loads((tmp_path / "summary.json").read_text())
    for s in (cli, r.summary):
        s.pop("wall_seconds")
    assert r.summary == cli
    assert r.summary["final"]["time"] == 5
    assert r.figures["max_tow_tension"] == cli["extremes"]["max_tow_tension"]["value"]
    assert r.node("z").shape == r.nodes.shape[:2]


def test_summary_has_the_discretisation_error_estimate():
    # paper 5.1 at its 5 elements: 0.12 % (docs/scenario.md "Accuracy"), below the 1 % warning.
    r = towsim.run(str(SCENARIOS / "paper-planar-a.yaml"), SHORT)
    assert r.summary["discretisation_error_estimate"] == 0.0012
    assert r.summary["warnings"] == []
    turn = towsim.run(str(SCENARIOS / "paper-3d-turn.yaml"), SHORT)
    assert turn.summary["discretisation_error_estimate"] == 0.059
    assert turn.summary["warnings"][0].startswith("discretisation error estimate 5.9 % of the tow tension exceeds 1 %")


def test_scenario_as_path_yaml_text_or_dict():
    path = SCENARIOS / "paper-3d-turn.yaml"
    by_path = towsim.run(pathlib.Path(path), SHORT)
    by_text = towsim.run(path.read_text(), SHORT)
    by_dict = towsim.run(by_path.summary["scenario"], SHORT)  # the scenario echo, as a dict
    for other in (by_text, by_dict):
        assert other.columns == by_path.columns
        assert np.array_equal(other.nodes, by_path.nodes)
        for c in by_path.columns:
            assert np.array_equal(other[c], by_path[c]), c


def test_overrides_have_the_semantics_of_set(tmp_path):
    path = SCENARIOS / "cable-tow.yaml"
    sets = {"simulation.duration": 2, "cable.elements": 4, "tow.motion.0.speed": 1.5,
            "cable.tangential_drag": {"law": "skin", "ct": 0.01}, "simulation.write_nodes": False}
    cli = ["--set", "simulation.duration=2", "--set", "cable.elements=4", "--set", "tow.motion.0.speed=1.5",
           "--set", "cable.tangential_drag={law: skin, ct: 0.01}", "--set", "simulation.write_nodes=false"]
    status, _, err = towsim_cli("run", path, "--out", tmp_path, "--quiet", *cli)
    assert status == 0, err
    r = towsim.run(path, sets)
    assert r.nodes is None and not (tmp_path / "nodes.csv").exists()
    assert_series_match_csv(r, tmp_path / "timeseries.csv")


def test_scenario_errors_carry_the_cli_messages(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text((SCENARIOS / "cable-tow.yaml").read_text().replace("diameter: 0.019", "diameter: -0.019")
                   .replace("added_mass: 1.0 ", "added_mas: 1.0 "))
    status, out, err = towsim_cli("run", bad, "--out", tmp_path / "out", "--set", "cable.elements=abc")
    assert status == 2
    assert not (tmp_path / "out").exists()
    with pytest.raises(towsim.ScenarioError) as e:
        towsim.run(str(bad), {"cable.elements": "abc"})
    assert isinstance(e.value, ValueError)
    assert str(e.value) + "\n" == err  # the same lines, in the same order
    assert len(e.value.errors) == 3
    assert e.value.errors[0].startswith(f"{bad}:")
    # YAML text and dicts are named <string> and <dict> in the messages.
    with pytest.raises(towsim.ScenarioError, match=r"^<string>:1:1: \(root\): expected a mapping"):
        towsim.run("- 1\n- 2\n")
    with pytest.raises(towsim.ScenarioError, match=r"cannot open|cannot read|no such"):
        towsim.run(str(tmp_path / "missing.yaml"))
    with pytest.raises(TypeError):
        towsim.run(42)


def test_a_scenario_that_contains_itself_is_a_value_error():
    # fuzz/fuzz_python.py found a RecursionError here (the dict was walked for ever).
    sc = {"cable": {"length": 20, "elements": 4, "mass_per_length": 1.5, "diameter": 0.02},
          "simulation": {"duration": 0.2}}
    sc["cable"]["sections"] = [sc["cable"]]
    with pytest.raises(ValueError, match=r"^scenario: a dict or list contains itself \(a circular reference\)$"):
        towsim.run(sc)


def test_scenario_errors_quoting_other_encodings_and_empty_sections(tmp_path):
    # A message quoting a byte that is not UTF-8 (once UnicodeDecodeError): U+FFFD in its place.
    bad = tmp_path / "b.yaml"
    bad.write_bytes(b'name: "\\\xff"\n')
    with pytest.raises(towsim.ScenarioError) as e:
        towsim.run(str(bad))
    assert e.value.errors[0].startswith(f"{bad}:1:")
    assert "\ufffd" in str(e.value)
    # An empty section list (once a crash of the interpreter) is a ScenarioError.
    with pytest.raises(towsim.ScenarioError) as e:
        towsim.run("cable: {sections: [], mass_per_length: 1.5, diameter: 0.02}\nsimulation: {duration: 1}\n")
    assert str(e.value) == ("<string>:1:19: cable.sections: the list is empty "
                            "(give at least one section, or leave sections out)")


def test_numerical_failure_raises_with_the_partial_result(tmp_path):
    path = tmp_path / "unstable.yaml"
    path.write_text(UNSTABLE)
    status, _, err = towsim_cli("run", path, "--out", tmp_path / "out", "--quiet")
    assert status == 3
    with pytest.raises(towsim.SimulationError) as e:
        towsim.run(path)
    r = e.value.result
    assert r.status == "failed"
    assert str(e.value) == r.message and r.message.startswith("numerical failure at t = ")
    assert r.message in err
    assert_series_match_csv(r, tmp_path / "out" / "timeseries.csv")  # the same rows up to the failure


def test_runs_in_two_threads_overlap_in_time():
    # The GIL is released while integrating: two runs started together are
    # inside their integrations at the same time. With the GIL held the second
    # could only start after the first returned (intervals disjoint). Asserted
    # on the integrations' own start/end timestamps, not on speed.
    path = SCENARIOS / "paper-3d-turn.yaml"
    sets = {"simulation.duration": 600, "simulation.write_nodes": False}  # about a second each
    barrier = threading.Barrier(2)
    results = [None, None]

    def work(i):
        barrier.wait()
        results[i] = towsim.run(path, sets)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    (s0, e0), (s1, e1) = (r.integration_interval for r in results)
    assert e0 > s0 and e1 > s1
    assert max(s0, s1) < min(e0, e1), ((s0, e0), (s1, e1))
    assert np.array_equal(results[0]["tow_tension"], results[1]["tow_tension"])


def test_ctrl_c_stops_the_run_and_keeps_the_result():
    # interrupt_main() is what Ctrl-C does to the main thread: the run stops
    # cleanly and towsim.Interrupted (a KeyboardInterrupt) carries its rows.
    # Python's own SIGINT handler, as in an interactive session (a process
    # started in the background by a shell inherits SIGINT ignored, and then
    # interrupt_main() does nothing).
    path = SCENARIOS / "paper-3d-turn.yaml"
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.3, _thread.interrupt_main)
    try:
        timer.start()
        t0 = time.monotonic()
        with pytest.raises(KeyboardInterrupt) as e:
            towsim.run(path, {"simulation.duration": 100000, "simulation.write_nodes": False})
    finally:
        timer.cancel()
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert isinstance(e.value, towsim.Interrupted)
    r = e.value.result
    assert r.status == "interrupted" and r.summary["status"] == "interrupted"
    assert 0 < r["time"][-1] < 100000
    assert time.monotonic() - t0 < 30  # it stopped, it did not run to the end


def test_ctrl_c_between_output_times_stops_promptly():
    # The next output time minutes of integration away: Ctrl-C is polled
    # after every step (once only at output times), the run stops within
    # seconds at the last row written (t = 0).
    path = SCENARIOS / "paper-3d-turn.yaml"
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, _thread.interrupt_main)
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt) as e:
            towsim.run(path, {"simulation.duration": 1e7, "simulation.output_interval": 5e6,
                              "simulation.write_nodes": False})
    finally:
        timer.cancel()
        timer.join()
        signal.signal(signal.SIGINT, previous)
    r = e.value.result
    assert r.status == "interrupted"
    assert list(r["time"]) == [0.0]
    assert r.integration_interval[1] - r.integration_interval[0] < 5  # 1 s asked for, margin for a loaded machine


def test_ctrl_c_stops_the_statics_and_keeps_the_last_iterate():
    # The steady solve runs in a worker thread while the main thread polls
    # Ctrl-C: a --target-depth search over 100000 elements (~2 s of CPU, many
    # solves) interrupted after 0.3 s raises towsim.Interrupted with the last
    # iterate, not converged.
    path = SCENARIOS / "paper-3d-turn.yaml"
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.3, _thread.interrupt_main)
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt) as e:
            towsim.statics(path, {"cable.elements": 100000}, target_depth=2000)
    finally:
        timer.cancel()
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert isinstance(e.value, towsim.Interrupted)
    assert e.value.result is not None and not e.value.result.converged


def test_statics_equals_the_cli_files(tmp_path):
    path = SCENARIOS / "paper-3d-turn.yaml"
    status, out, err = towsim_cli("statics", path, "--out", tmp_path)
    assert status == 0, err
    s = towsim.statics(path)
    assert s.converged and s.iterations > 0
    header, rows = read_csv(tmp_path / "timeseries.csv")
    assert header == s.columns and len(rows) == 1
    for j, c in enumerate(header):
        assert same_printed(s[c], rows[0][j]), c
    nheader, nrows = read_csv(tmp_path / "nodes.csv")
    assert nheader[2:] == s.node_columns and len(nrows) == s.nodes.shape[0]
    for k, row in enumerate(nrows):
        for c in range(len(s.node_columns)):
            assert same_printed(s.nodes[k, c], row[2 + c]), (k, c)
    with pytest.raises(towsim.ScenarioError, match="statics needs mode: motion"):
        towsim.statics(path, {"tow.mode": "force", "tow.force": [10, 0, 0], "tow.motion": None})


def test_examples_are_available():
    assert "paper-3d-turn" in towsim.examples()
    r = towsim.run(towsim.example("cable-tow"), {"simulation.duration": 1})
    assert r["time"][-1] == 1
    with pytest.raises(towsim.ScenarioError):
        towsim.example("nope")


def test_statics_target_depth_equals_the_cli():
    # towsim.statics(..., target_depth=D) is `towsim statics --target-depth D`.
    path = SCENARIOS / "fish-depth-change.yaml"
    status, out, err = towsim_cli("statics", path, "--target-depth", "300")
    assert status == 0, err
    s = towsim.statics(path, target_depth=300)
    assert s.converged
    assert f"deployed length for a depth of 300 m: {s.deployed_length:.7g} m" in out
    assert abs(s["body_depth"] - 300) < 1e-6
    assert abs(s["deployed_length"] - s.deployed_length) < 1e-6
    assert towsim.statics(path).deployed_length is None
