"""towsim.run, towsim.statics and towsim.sweep on networks (`lines:`): the
same numbers as the command line's files, and the bridle at rest against
its statics by hand (W / (2 cos(asin(b/a))) per leg)."""
import json
import math

import pytest

import towsim
from conftest import SOURCE, read_csv, same_printed, towsim_cli

BRIDLE = SOURCE / "examples" / "bridled-towfish.yaml"
SHORT = {"simulation.duration": 5}

# The bridle at rest: a 100 kg sphere of radius 0.2 m hung from a junction
# by two light legs (a = 2 m, hull points 2b = 2 m apart), as in
# tests/unit/test_cli_network.cpp.
AT_REST = (SOURCE / "tests" / "support" / "bridle-at-rest.yaml").read_text()
# W / (2 cos(asin(b / a))), W the box's apparent weight [N]; the legs weigh
# 0.02 N in water: the tolerance.
LEG = (100 - 1025 * 4.0 / 3 * math.pi * 0.008) * 9.81 / (2 * math.cos(math.asin(0.5)))
LEG_WEIGHT = 0.02


def test_network_run_equals_the_cli_files(tmp_path):
    status, _, err = towsim_cli("run", BRIDLE, "--out", tmp_path, "--set", "simulation.duration=5", "--quiet")
    assert status == 0, err
    r = towsim.run(BRIDLE, SHORT)
    assert r.status == "ok"
    # Every number of timeseries.csv, to the 12 printed digits.
    header, rows = read_csv(tmp_path / "timeseries.csv")
    assert header == r.columns and len(rows) == len(r["time"])
    for j, c in enumerate(header):
        for i, row in enumerate(rows):
            assert same_printed(r[c][i], row[j]), (c, i)
    # nodes.csv: per time, each line's joints in turn.
    nheader, nrows = read_csv(tmp_path / "nodes.csv")
    assert nheader == ["line", "time", "node"] + r.node_columns
    assert list(r.nodes) == ["main", "leg_fwd", "leg_aft"]
    it = iter(nrows)
    for i in range(len(r["time"])):
        for line, a in r.nodes.items():
            for k in range(a.shape[1]):
                row = next(it)
                assert row[0] == line and int(row[2]) == k
                for c in range(a.shape[2]):
                    assert same_printed(a[i, k, c], row[3 + c]), (line, i, k, c)
    assert r.node("z")["main"].shape == r.nodes["main"].shape[:2]
    # summary.json: the same document but for the wall-clock time.
    cli = json.loads((tmp_path / "summary.json").read_text())
    for s in (cli, r.summary):
        s.pop("wall_seconds")
    assert r.summary == cli
    assert r.figures["max_main_top_tension"] == cli["extremes"]["max_main_top_tension"]["value"]


def test_network_statics_is_the_bridle_by_hand_and_the_cli(tmp_path):
    s = towsim.statics(AT_REST)
    assert s.converged and s.iterations > 0 and s.residual < 1e-6
    for leg in ("leg_a", "leg_b"):
        assert abs(s[f"{leg}_top_tension"] - LEG) < LEG_WEIGHT, leg
    assert set(s.nodes) == {"main", "leg_a", "leg_b"} and s.nodes["main"].shape == (6, len(s.node_columns))
    # `towsim statics --out`'s one row, to the 12 printed digits.
    scenario = tmp_path / "bridle.yaml"
    scenario.write_text(AT_REST)
    status, _, err = towsim_cli("statics", scenario, "--out", tmp_path / "out")
    assert status == 0, err
    header, rows = read_csv(tmp_path / "out" / "timeseries.csv")
    assert header == s.columns and len(rows) == 1
    for j, c in enumerate(header):
        assert same_printed(s[c], rows[0][j]), c
    # The run that settles: the same leg tensions at its end.
    r = towsim.run(AT_REST)
    for leg in ("leg_a", "leg_b"):
        assert abs(r[f"{leg}_top_tension"][-1] - LEG) < LEG_WEIGHT, leg


def test_network_sweep_rows_are_its_runs(tmp_path):
    cases = towsim.grid(BRIDLE, {"lines.0.length": [150, 200]}, fixed={**SHORT, "simulation.write_nodes": False})
    table = towsim.sweep(cases, max_workers=1, frame=False)
    assert list(table["status"]) == ["ok", "ok"]
    for i, (_, overrides) in enumerate(cases):
        figures = towsim.run(BRIDLE, overrides).figures
        for name in ("max_main_top_tension", "max_fish_depth", "final_fish_depth", "final_leg_aft_top_tension"):
            assert table[name][i] == figures[name], (name, i)
    # The longer main line tows the fish deeper.
    assert table["final_fish_depth"][1] > table["final_fish_depth"][0]
    steady = towsim.sweep(cases, max_workers=1, frame=False, statics=True)
    assert list(steady["status"]) == ["ok", "ok"]
    for i, (_, overrides) in enumerate(cases):
        s = towsim.statics(BRIDLE, overrides)
        assert same_printed(s["fish_depth"], f"{steady['final_fish_depth'][i]:.12g}")


TWO = (SOURCE / "tests" / "support" / "two-spheres-at-rest.yaml").read_text()


def test_network_target_depth_on_a_chosen_line():
    # Each sphere hangs 0.2 m below its line's end: 14.8 m of line la for 15 m
    # (2e-3 m: the search's 1 mm), line lb left at its 20 m.
    s = towsim.statics(TWO, target_depth=15, line="la")
    assert abs(s.deployed_length - 14.8) < 2e-3
    assert abs(s["a_depth"] - 15) < 2e-3 and abs(s["lb_deployed_length"] - 20) < 1e-9
    with pytest.raises(towsim.SimulationError, match="choose the one whose length varies: --line NAME"):
        towsim.statics(TWO, target_depth=15)
    with pytest.raises(towsim.ScenarioError, match="line: lc: no line of that name from the vessel"):
        towsim.statics(TWO, target_depth=15, line="lc")
