"""towsim from Python: runs, statics and parameter sweeps (docs/python.md).

    import towsim
    r = towsim.run("scenarios/paper-3d-turn.yaml", {"simulation.duration": 60})
    r["tow_tension"]          # NumPy array, one value per output time
    r.nodes[:, -1, 2]         # z of the last joint over time (time x joint x component)
    r.summary["extremes"]["max_tow_tension"]["value"]

A scenario is a path (str or os.PathLike), a YAML string or a dict; overrides
are a dict of dotted keys with the semantics of the command line's --set.
"""

import itertools
import json
import math
import os
from collections.abc import Mapping

import numpy as np

from . import _towsim as _core

__all__ = [
    "Interrupted", "Result", "ScenarioError", "SimulationError", "StaticsResult", "example", "examples",
    "grid", "run", "statics", "sweep", "towing_table",
]


class ScenarioError(ValueError):
    """An invalid scenario or override. str() is every error, one per line,
    as the command line prints them: FILE:LINE:COL: key.path: problem.
    `errors` holds the lines."""

    def __init__(self, message):
        message = message.rstrip("\n")
        super().__init__(message)
        self.errors = message.splitlines()


class SimulationError(RuntimeError):
    """The simulation failed numerically. `result` holds what was computed
    until then (a Result with status 'failed'); str() is the message."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during a run: the run stopped cleanly; `result` holds the
    samples computed until then (status 'interrupted')."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class Result(Mapping):
    """A run's outputs. As a mapping: the time series, one NumPy array per
    timeseries.csv column (r["time"], r["tow_tension"], ...).

    nodes: array time x joint x component (components `node_columns`: the
    nodes.csv columns x, y, z, vx, vy, vz, tension, axial_force, strain), or None when
    simulation.write_nodes is false; for a network (`lines:`) a dict of line
    name -> that line's array. summary: summary.json as a dict.
    status and message: as in summary.json. integration_interval: (start,
    end) of the integration on time.monotonic()'s clock [s]."""

    def __init__(self, raw):
        self.columns = list(raw["columns"])
        table = raw["series"]
        self.series = {c: table[:, i] for i, c in enumerate(self.columns)}
        self.node_columns = list(raw["node_columns"])
        self.nodes = raw["nodes"]
        self._summary_text = raw["summary"]
        self.summary = json.loads(raw["summary"])
        self.status = raw["status"]
        self.message = raw["message"]
        # (start, end) of the integration on time.monotonic()'s clock [s]
        self.integration_interval = tuple(raw["integration_interval"])

    def __getitem__(self, column):
        return self.series[column]

    def __iter__(self):
        return iter(self.columns)

    def __len__(self):
        return len(self.columns)

    def node(self, component):
        """One nodes.csv column as an array time x joint (e.g. r.node("tension"));
        for a network a dict of line name -> that array."""
        if self.nodes is None:
            raise KeyError("no nodes recorded (simulation.write_nodes is false)")
        c = self.node_columns.index(component)
        if isinstance(self.nodes, dict):
            return {line: a[:, :, c] for line, a in self.nodes.items()}
        return self.nodes[:, :, c]

    @property
    def figures(self):
        """The summary's figures by their sweep-table names (max_tow_tension, final_end_depth, ...)."""
        return dict(_core.summary_figures(self._summary_text))

    def __repr__(self):
        n = len(self.series["time"]) if self.columns else 0
        return f"<towsim.Result {self.status}: {n} samples, {len(self.columns)} columns>"


class StaticsResult(Mapping):
    """A steady-tow equilibrium. As a mapping: its one timeseries row by
    column name (floats); nodes: array joint x component (node_columns);
    converged, iterations, residual [rad/s^2], message, tow_velocity [m/s].
    For a network (`lines:`): nodes is a dict of line name -> that array,
    iterations the relaxation's steps and residual the joints' speed left
    relative to the tow [m/s]."""

    def __init__(self, raw):
        self.columns = list(raw["columns"])
        self.values = {c: float(v) for c, v in zip(self.columns, raw["values"])}
        self.node_columns = list(raw["node_columns"])
        self.nodes = raw["nodes"]
        self.converged = bool(raw["converged"])
        self.iterations = int(raw["iterations"])
        self.residual = float(raw["residual"])
        self.message = raw["message"]
        self.tow_velocity = np.array(raw["tow_velocity"])
        self.deployed_length = float(raw["deployed_length"]) if "deployed_length" in raw else None

    def __getitem__(self, column):
        return self.values[column]

    def __iter__(self):
        return iter(self.columns)

    def __len__(self):
        return len(self.columns)

    def __repr__(self):
        return f"<towsim.StaticsResult converged={self.converged} iterations={self.iterations}>"


def _looks_like_yaml(text):
    return "\n" in text or ": " in text or text.lstrip().startswith("{") or text.rstrip().endswith(":")


def _source(scenario):
    """(kind, source, label) for the core: a file, YAML text or a dict."""
    if isinstance(scenario, Mapping):
        return "text", json.dumps(_plain(scenario)), "<dict>"
    if isinstance(scenario, os.PathLike):
        return "file", os.fspath(scenario), ""
    if isinstance(scenario, str):
        if _looks_like_yaml(scenario) and not os.path.isfile(scenario):
            return "text", scenario, "<string>"
        return "file", scenario, ""
    raise TypeError(f"scenario: expected a path, a YAML string or a dict (got {type(scenario).__name__})")


def _plain(value, _open=()):
    """NumPy scalars and arrays as plain Python values (for JSON). A dict or
    list that contains itself is a ValueError (it has no YAML form)."""
    if isinstance(value, (Mapping, list, tuple)):
        if id(value) in _open:
            raise ValueError("scenario: a dict or list contains itself (a circular reference)")
        _open = _open + (id(value),)
    if isinstance(value, Mapping):
        return {str(k): _plain(v, _open) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v, _open) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value


def _value_text(value):
    """A Python value as the VALUE of --set KEY=VALUE (read as YAML)."""
    value = _plain(value)
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return ".nan"
        if math.isinf(value):
            return ".inf" if value > 0 else "-.inf"
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return value
    return json.dumps(value)


def _sets(overrides):
    if overrides is None:
        return []
    if not isinstance(overrides, Mapping):
        raise TypeError(f"overrides: expected a dict of dotted keys (got {type(overrides).__name__})")
    return [f"{k}={_value_text(v)}" for k, v in overrides.items()]


def run(scenario, overrides=None):
    """Simulate `scenario` with `overrides` ({"dotted.key": value}, as --set).

    Returns a Result. Raises ScenarioError for invalid input, SimulationError
    (with .result, the partial run) for a numerical failure, Interrupted (a
    KeyboardInterrupt, with .result) on Ctrl-C. The GIL is released while
    integrating, so runs in several threads proceed in parallel."""
    raw = _core.run(*_source(scenario), _sets(overrides))
    if "errors" in raw:
        raise ScenarioError(raw["errors"])
    result = Result(raw)
    if raw["keyboard_interrupt"]:
        raise Interrupted(result.message, result)
    if result.status == "failed":
        raise SimulationError(result.message, result)
    return result


def statics(scenario, overrides=None, target_depth=None, line=None):
    """The steady-tow equilibrium at the tow law's final speed (`towsim statics`).

    With target_depth [m]: first the deployed cable length that puts the body
    (or the cable end) at that depth (`--target-depth`), in .deployed_length;
    the equilibrium is then the one at that length. For a network with
    several lines from the vessel, `line` names the one whose length varies
    (`--line`), for the deepest body below it.
    Returns a StaticsResult; raises ScenarioError for invalid input and
    SimulationError (with .result) when the solver does not converge, and
    Interrupted (with .result, the last iterate) on Ctrl-C."""
    if target_depth is not None and not target_depth > 0:
        raise ScenarioError(f"--target-depth must be > 0 (got {target_depth})")
    args = (*_source(scenario), _sets(overrides))
    if target_depth is None:
        raw = _core.statics(*args) if line is None else _core.statics(*args, line=str(line))
    else:
        raw = _core.statics(*args, float(target_depth), "" if line is None else str(line))
    if "errors" in raw:
        raise ScenarioError(raw["errors"])
    result = StaticsResult(raw)
    if raw.get("keyboard_interrupt"):
        raise Interrupted("interrupted", result)
    if not result.converged:
        raise SimulationError(result.message, result)
    return result


def examples():
    """The names of the built-in example scenarios."""
    return list(_core.examples())


def example(name):
    """A built-in example's YAML text (a scenario for run(), statics(), sweep())."""
    text = _core.example_yaml(name)
    if text is None:
        raise ScenarioError(f"--example:1:1: {name}: unknown example; towsim.examples() lists them")
    return text


def grid(scenario, axes, fixed=None):
    """Cases for sweep(): every combination of `axes` ({"key": [values]}),
    the first key varying slowest (as a sweep file's grid), each with the
    `fixed` overrides too."""
    keys = list(axes)
    cases = []
    for combo in itertools.product(*(list(axes[k]) for k in keys)):
        overrides = dict(fixed or {})
        overrides.update(zip(keys, combo))
        cases.append((scenario, overrides))
    return cases


def _case(scenario, overrides, statics=False):
    """One sweep case (runs in a worker): (status, message, [(figure, value)])."""
    kind, source, label = _source(scenario)
    try:
        sets = _sets(overrides)
    except TypeError as e:
        return "invalid", str(e), []
    status, message, figures = _core.run_case(kind, source, label, sets, "", bool(statics))
    return status, message, list(figures)


def _portable(scenario):
    """A scenario path made absolute, so that workers elsewhere find it."""
    if isinstance(scenario, os.PathLike) or (isinstance(scenario, str) and os.path.isfile(scenario)):
        return os.path.abspath(os.fspath(scenario))
    return scenario


def sweep(cases, executor=None, *, max_workers=None, frame=None, statics=False):
    """Run many cases and gather one row per case.

    cases: a list of (scenario, overrides) pairs (see grid()). executor: any
    concurrent.futures.Executor, or a dask.distributed Client; None = a
    ProcessPoolExecutor with `max_workers` processes (default: every core).
    Each case runs exactly as a `towsim sweep` case; with statics=True, as a
    `statics: true` sweep's case: the steady tow of `towsim statics` (the
    `final_*` figures are the equilibrium's). A case that fails is a row with
    its status ('failed', 'invalid') and message.

    Returns a pandas DataFrame (one row per case, in order: the override
    columns, status, message, then the summary's figures by name) when pandas
    is installed (or frame=True), else (or frame=False) a dict of NumPy arrays."""
    cases = [(_portable(s), dict(o or {})) for s, o in cases]
    own = executor is None
    if own:
        from concurrent.futures import ProcessPoolExecutor

        executor = ProcessPoolExecutor(max_workers=max_workers or os.cpu_count() or 1)
    futures = []
    try:
        futures = [executor.submit(_case, s, o, bool(statics)) for s, o in cases]
        outcomes = [f.result() for f in futures]
    except BaseException:  # Ctrl-C, or a worker lost: stop what is left
        for f in futures:
            f.cancel()
        if own:  # our processes: end them now rather than after the cases already queued
            for p in list((getattr(executor, "_processes", None) or {}).values()):
                p.terminate()
        raise
    finally:
        if own:
            executor.shutdown(wait=True, cancel_futures=True)
    return _table(cases, outcomes, frame)


def towing_table(table, frame=None):
    """The towing table of a sweep() result (the columns of a sweep's
    towing_table.csv): the override columns, status, then tow_speed [m/s],
    tow_speed_kn, depth [m] (of the end body, or the cable end), layback [m],
    tow_tension [N], top_angle_deg (the cable below the horizontal at the tow
    point), offset_aft and offset_starboard [m] (of the end body or cable end
    from the tow point, along and across the tow's heading). A DataFrame or a
    dict of arrays as `frame` says (default: what `table` is)."""
    names = list(table.keys()) if isinstance(table, Mapping) else list(table.columns)
    first = names.index("message")
    figures = names[first + 1:]
    n = len(table["status"])
    rows = [_core.towing_row([(f, float(table[f][i])) for f in figures]) for i in range(n)]
    columns = {k: np.asarray(table[k]) for k in names[:first]}
    for j, name in enumerate(_core.towing_table_columns()):
        columns[name] = np.array([r[j] for r in rows], dtype=float)
    if frame is None:
        frame = not isinstance(table, dict)
    if not frame:
        return columns
    import pandas
    return pandas.DataFrame(columns)


def _table(cases, outcomes, frame):
    keys, figures = [], []
    for _, overrides in cases:
        keys += [k for k in overrides if k not in keys]
    rows = []
    for (_, overrides), (status, message, figs) in zip(cases, outcomes):
        figs = dict(figs)
        figures += [f for f in figs if f not in figures]
        rows.append((overrides, status, message, figs))
    columns = {k: np.array([o.get(k) for o, _, _, _ in rows], dtype=object) for k in keys}
    columns["status"] = np.array([s for _, s, _, _ in rows], dtype=object)
    columns["message"] = np.array([m for _, _, m, _ in rows], dtype=object)
    for f in figures:
        columns[f] = np.array([fg.get(f, math.nan) for _, _, _, fg in rows], dtype=float)
    for k in keys:  # numbers as numbers, where every value is one
        try:
            if all(isinstance(_plain(v), (int, float)) and not isinstance(v, bool) for v in columns[k]):
                columns[k] = columns[k].astype(float)
        except (TypeError, ValueError):
            pass
    if frame is False:
        return columns
    try:
        import pandas
    except ImportError:
        if frame:
            raise
        return columns
    return pandas.DataFrame(columns)
