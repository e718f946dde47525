"""towsim.sweep on a Dask distributed LocalCluster (2 worker processes on
the loopback interface, started by the test) gives the local table (issue 16)."""
import pytest

import towsim
from conftest import SCENARIOS, read_csv, same_printed, towsim_cli

distributed = pytest.importorskip("distributed")
pandas = pytest.importorskip("pandas")


def test_dask_sweep_equals_local_sweep(tmp_path):
    cases = towsim.grid(SCENARIOS / "paper-3d-turn.yaml",
                        {"tow.motion.0.speed": [1.0, 1.57, 2.0], "cable.elements": [4, 6]},
                        fixed={"simulation.duration": 4, "simulation.write_nodes": False})
    cases.append((str(SCENARIOS / "cable-tow.yaml"), {"cable.elements": 0}))  # an invalid case: a row too
    local = towsim.sweep(cases, max_workers=2)
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None, local_directory=str(tmp_path)) as cluster, \
            distributed.Client(cluster) as client:
        remote = towsim.sweep(cases, client)
        # Both workers took part.
        assert len(client.scheduler_info()["workers"]) == 2
        # Steady tows through the same path: each case exactly towsim.statics's.
        speeds = [1.0, 1.57, 2.0]
        steady = towsim.sweep(towsim.grid(SCENARIOS / "paper-3d-turn.yaml", {"tow.motion.0.speed": speeds}), client,
                              statics=True)
    assert list(steady["status"]) == ["ok"] * 3
    for i, speed in enumerate(speeds):
        s = towsim.statics(SCENARIOS / "paper-3d-turn.yaml", {"tow.motion.0.speed": speed})
        assert steady["final_tow_tension"][i] == s["tow_tension"] and steady["final_end_depth"][i] == s["end_depth"]
    assert isinstance(remote, pandas.DataFrame)
    assert list(remote["status"]) == ["ok"] * 6 + ["invalid"]
    # Deterministic runs: the same numbers bit for bit, row for row.
    pandas.testing.assert_frame_equal(remote, local)
    # And the table of `towsim sweep --jobs 1` for the same grid, to its printed digits.
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text(f"""scenario: {SCENARIOS / 'paper-3d-turn.yaml'}
set: {{simulation.duration: 4, simulation.write_nodes: false}}
grid: {{tow.motion.0.speed: [1.0, 1.57, 2.0], cable.elements: [4, 6]}}
""")
    status, _, err = towsim_cli("sweep", sweep, "--out", tmp_path / "cli", "--jobs", "1", "--quiet")
    assert status == 0, err
    header, rows = read_csv(tmp_path / "cli" / "sweep.csv")
    assert len(rows) == 6
    for i, row in enumerate(rows):
        assert row[header.index("status")] == remote["status"][i]
        for name in header[header.index("message") + 1:]:
            assert same_printed(remote[name][i], row[header.index(name)]), (i, name)
