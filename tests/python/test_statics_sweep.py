"""Sweeps of steady tows (`statics: true`, towsim.sweep(..., statics=True)):
each case is exactly a `towsim statics`; the towing table holds its figures."""
import json
import math
import re

import pytest

import towsim
from conftest import SCENARIOS, read_csv, same_printed, towsim_cli

TOWING = SCENARIOS.parent / "examples" / "towing.yaml"
SPEEDS = [1.0289, 2.0578, 3.0867]  # [m/s]: 2, 4, 6 kn
KNOT = 1852.0 / 3600.0  # [m/s]


def statics_sweep(tmp_path, extra=""):
    path = tmp_path / "sweep.yaml"
    path.write_text(f"""scenario: {TOWING}
statics: true
grid:
  tow.motion.0.speed: {SPEEDS}
{extra}""")
    return path


def cli_statics(tmp_path, sets, name):
    """`towsim statics --out`: (summary.json as a dict, stdout)."""
    out = tmp_path / name
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={v}")]
    status, stdout, err = towsim_cli("statics", TOWING, *args, "--out", out)
    assert status == 0, err
    return json.loads((out / "summary.json").read_text()), stdout


def test_a_statics_sweep_gives_what_towsim_statics_gives(tmp_path):
    status, _, err = towsim_cli("sweep", statics_sweep(tmp_path), "--out", tmp_path / "out", "--quiet")
    assert status == 0, err
    header, rows = read_csv(tmp_path / "out" / "sweep.csv")
    assert [r[1] for r in rows] == [str(v) for v in SPEEDS]
    assert all(r[header.index("status")] == "ok" for r in rows)
    for i, row in enumerate(rows):
        summary, _ = cli_statics(tmp_path, {"tow.motion.0.speed": SPEEDS[i]}, f"statics-{i}")
        figures = dict(towsim._core.summary_figures(json.dumps(summary)))
        # Every figure of the row, to the 12 digits both files print: the same solve.
        assert header[header.index("message") + 1:] == list(figures)
        for name in figures:
            assert same_printed(figures[name], row[header.index(name)]), (i, name)
        # The equilibrium's, not a run's: one sample at t = 0.
        assert row[header.index("end_time")] == "0"
        assert float(row[header.index("final_layback")]) == summary["final"]["layback"]


def test_the_towing_table_csv(tmp_path):
    # A current from port to starboard: the fish is carried to starboard.
    status, _, err = towsim_cli("sweep", statics_sweep(tmp_path, "set: {environment.current: [0, -0.2, 0]}\n"),
                                "--out", tmp_path / "out", "--quiet")
    assert status == 0, err
    header, rows = read_csv(tmp_path / "out" / "sweep.csv")
    t_header, t_rows = read_csv(tmp_path / "out" / "towing_table.csv")
    assert t_header == ["case", "tow.motion.0.speed", "status", "tow_speed", "tow_speed_kn", "depth", "layback",
                        "tow_tension", "top_angle_deg", "offset_aft", "offset_starboard"]
    assert len(t_rows) == len(SPEEDS)
    for i, (row, t) in enumerate(zip(rows, t_rows)):
        col = dict(zip(t_header, t))
        fig = dict(zip(header, row))
        assert col["case"] == str(i) and col["status"] == "ok"
        # The sweep's own figures, as they are.
        assert col["depth"] == fig["final_body_depth"]
        assert col["layback"] == fig["final_layback"]
        assert col["tow_tension"] == fig["final_tow_tension"]
        # The tow speed: the tow law's, in m/s and knots (to the 12 printed digits).
        assert float(col["tow_speed"]) == pytest.approx(SPEEDS[i], rel=1e-11)
        assert float(col["tow_speed_kn"]) == pytest.approx(SPEEDS[i] / KNOT, rel=1e-11)
        # The offsets split the layback into along and across the heading (+x):
        # Pythagoras to the printed digits' round-off (1e-10 relative).
        aft, stbd = float(col["offset_aft"]), float(col["offset_starboard"])
        assert math.hypot(aft, stbd) == pytest.approx(float(col["layback"]), rel=1e-10)
        assert aft == pytest.approx(float(fig["final_tow_x"]) - float(fig["final_body_x"]), rel=1e-10)
        assert stbd == pytest.approx(float(fig["final_tow_y"]) - float(fig["final_body_y"]), rel=1e-10)
        assert aft > 0 and stbd > 0
        # The top angle: the tow force's angle above the horizontal that
        # `towsim statics` prints (6 digits there).
        _, stdout = cli_statics(tmp_path, {"tow.motion.0.speed": SPEEDS[i], "environment.current": "[0, -0.2, 0]"},
                                f"statics-{i}")
        printed = float(re.search(r"tension [-0-9.e+]+ N, ([-0-9.e+]+) deg above horizontal", stdout).group(1))
        assert float(col["top_angle_deg"]) == pytest.approx(printed, abs=5e-4 * max(1.0, abs(printed)))
    # Faster: shallower and a flatter cable at the top.
    depth = [float(r[t_header.index("depth")]) for r in t_rows]
    angle = [float(r[t_header.index("top_angle_deg")]) for r in t_rows]
    assert depth == sorted(depth, reverse=True) and angle == sorted(angle, reverse=True)


def test_a_statics_sweep_needs_a_tow_law(tmp_path):
    sweep = statics_sweep(tmp_path, "set: {initial: hanging, tow.mode: force, tow.force: [2000, 0, 0]}\n")
    status, out, err = towsim_cli("sweep", sweep, "--out", tmp_path / "out")
    assert status == 2 and out == ""
    assert err == (f"{sweep}:5:35: tow.mode: statics needs mode: motion (the steady speed comes from the tow law; "
                   "got force)\n")
    assert not (tmp_path / "out").exists()


def test_python_statics_sweep_equals_the_cli_and_towsim_statics(tmp_path):
    status, _, err = towsim_cli("sweep", statics_sweep(tmp_path), "--out", tmp_path / "out", "--jobs", "1", "--quiet")
    assert status == 0, err
    header, rows = read_csv(tmp_path / "out" / "sweep.csv")
    cases = towsim.grid(TOWING, {"tow.motion.0.speed": SPEEDS})
    table = towsim.sweep(cases, max_workers=2, frame=False, statics=True)
    assert list(table["status"]) == ["ok"] * len(SPEEDS)
    for i, speed in enumerate(SPEEDS):
        s = towsim.statics(TOWING, {"tow.motion.0.speed": speed})
        # The same solve, in another process: the same doubles.
        for column in s:
            assert table[f"final_{column}"][i] == s[column] or (math.isnan(s[column])
                                                                and math.isnan(table[f"final_{column}"][i]))
        for name in header[header.index("message") + 1:]:
            assert same_printed(table[name][i], rows[i][header.index(name)]), (i, name)
    # towsim.towing_table: the columns of towing_table.csv, the same values.
    t_header, t_rows = read_csv(tmp_path / "out" / "towing_table.csv")
    tt = towsim.towing_table(table)
    assert list(tt) == [h for h in t_header if h != "case"]
    for i, row in enumerate(t_rows):
        for name in t_header[3:]:
            assert same_printed(tt[name][i], row[t_header.index(name)]), (i, name)


def test_towsim_plot_draws_a_sweeps_towing_table(tmp_path):
    status, _, err = towsim_cli("sweep", statics_sweep(tmp_path), "--out", tmp_path / "out", "--quiet")
    assert status == 0, err
    status, _, log = towsim_cli("plot", tmp_path / "out")
    assert status == 0, log
    plots = tmp_path / "out" / "plots"
    assert log == f"towsim plot: wrote {plots / 'towing_table.png'} and .svg\n"
    for ext in ("png", "svg"):
        assert (plots / f"towing_table.{ext}").stat().st_size > 0
    script = (plots / "towing_table.gp").read_text()
    # Units on both axes, depth downwards (0 at the top), each point labelled.
    assert "set xlabel 'layback: horizontal distance from the tow point (m)'" in script
    assert "set ylabel 'depth of the body (or cable end) (m), downwards'" in script
    assert re.search(r"set yrange \[[0-9.]+:0\]", script)
    assert "sprintf('%d: %.3g kn', column('case'), column('tow_speed_kn'))" in script
    svg = (plots / "towing_table.svg").read_text()
    for i, kn in enumerate(("2", "4", "6")):
        assert f"{i}: {kn} kn" in svg
