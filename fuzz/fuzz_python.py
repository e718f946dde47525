"""Fuzzing the Python entry points: towsim.run, towsim.statics, towsim.sweep.

Mutated scenarios (dicts, YAML strings, paths) and overrides (dicts of dotted
keys with values of every Python type) from a fixed seed. Each call must
return or raise what the module documents: ScenarioError for invalid input,
SimulationError for a numerical failure, TypeError or ValueError for an
argument of the wrong kind. Anything else (another exception, a crash of the
interpreter, which the caller sees as the exit status) is a finding: the
input is written to REPRO and the exit status is 1.

  PYTHONPATH=build/python python3 fuzz/fuzz_python.py [--runs N] [--seed S] [--seconds T] [--repro FILE]

Every run is capped at 0.2 simulated seconds (an override given last), so a
valid input costs milliseconds; numbers are drawn from a pool that holds no
valid but expensive count (element counts are 3 or beyond the limits).
"""
import argparse
import concurrent.futures
import copy
import math
import os
import random
import sys
import tempfile
import time

import numpy as np

import towsim

BASE = {
    "name": "fuzz",
    "cable": {"length": 20, "elements": 4, "mass_per_length": 1.5, "diameter": 0.02},
    "body": {"mass": 20, "inertia": [1, 1, 1], "link_point": [0, 0, 0.2],
             "spheres": [{"center": [0, 0, 0], "radius": 0.2, "drag": 0.5}]},
    "tow": {"motion": [{"type": "ramp", "direction": [1, 0, 0], "speed": 1.0, "ramp_time": 2},
                       {"type": "turn", "radius": 20, "start_time": 3, "side": "port"}]},
    "simulation": {"duration": 0.2, "output_interval": 0.1},
}

KEYS = ["cable.length", "cable.elements", "cable.mass_per_length", "cable.diameter", "cable.sections",
        "cable.sections.0.length", "cable.axial_stiffness", "cable.bending_stiffness", "cable.attachments",
        "body.mass", "body.inertia", "body.spheres.0.radius", "body.link_point", "tow.motion.0.speed",
        "tow.motion.0.speed_kn", "tow.motion.1.radius", "tow.mode", "tow.force", "simulation.integrator",
        "simulation.formulation", "simulation.tolerance", "simulation.time_step", "simulation.threads",
        "initial", "environment.seabed.depth", "environment.current", "waves.regular.height", "winch",
        "name", "", ".", "cable..length", "cable.sections.99.length", "tow.motion.-1.speed"]

TEXTS = ["", " ", ":", ", {", "[", "{a: [", "cable: {length: 10", "- 1\n- 2", "\t- x", "---\n---\nfoo: 1",
         "&a [*a]", "\"\\xff\"", "\udcff", "nan", "~", "null", "cable: !!binary aGk=", "\x00\x01\x02",
         "cable: {length: 10, elements: 2, mass_per_length: 1, diameter: 0.01}\nsimulation: {duration: 0.1}\n"]


def number(rng):
    return rng.choice([0, -1, 1, 3, 0.5, -0.0, 1e-300, -1e300, 1e300, math.nan, math.inf, -math.inf,
                       2**63, -2**63, 10**30, np.float32(2.5), np.int64(3), True, False])


def value(rng, depth=0):
    """A value of any type the module might be handed (mostly numbers and text)."""
    r = rng.random()
    if r < 0.35:
        return number(rng)
    if r < 0.50:
        return rng.choice(TEXTS)
    if r < 0.55:
        return None
    if r < 0.60:
        return rng.choice([b"\xff\xfe", bytearray(b"x"), object(), 1j, range(3), {1, 2}])
    if r < 0.65:
        return np.array([number(rng) for _ in range(rng.randrange(4))], dtype=float)
    if r < 0.75 or depth >= 2:
        return copy.deepcopy(rng.choice(list(BASE["tow"]["motion"][0].values()) + [[0, 0, 1], 2.0, "port", "rk4", "steady"]))
    if r < 0.90:
        return [value(rng, depth + 1) for _ in range(rng.randrange(4))]
    return {rng.choice(KEYS + ["type", "radius", 7, None]): value(rng, depth + 1) for _ in range(rng.randrange(3))}


def mutate(rng, tree):
    """Replace, delete or add one entry somewhere in a nested dict/list."""
    node = tree
    for _ in range(rng.randrange(4)):
        if isinstance(node, dict) and node:
            child = node[rng.choice(list(node))]
        elif isinstance(node, list) and node:
            child = rng.choice(node)
        else:
            break
        if not isinstance(child, (dict, list)):
            break
        node = child
    if isinstance(node, dict):
        op = rng.randrange(3)
        if op == 0 and node:
            del node[rng.choice(list(node))]
        elif op == 1 and node:
            node[rng.choice(list(node))] = value(rng)
        else:
            node[rng.choice(KEYS + ["unknown", "Cable", "simulation"])] = value(rng)
    elif isinstance(node, list):
        if node and rng.random() < 0.5:
            node[rng.randrange(len(node))] = value(rng)
        else:
            node.append(value(rng))


def scenario(rng, tmp):
    """A scenario as a dict, a YAML string or a path."""
    kind = rng.randrange(10)
    tree = copy.deepcopy(BASE)
    for _ in range(rng.randrange(1, 4)):
        mutate(rng, tree)
    if kind < 6:
        if rng.random() < 0.02:  # a dict that contains itself
            tree["self"] = tree
        return tree
    if kind < 8:
        return rng.choice(TEXTS) + rng.choice(["", "\n", "\nsimulation: {duration: 0.1}\n"])
    if kind == 8:
        return rng.choice([os.path.join(tmp, "missing.yaml"), tmp, "/dev/null", ""])
    return rng.choice([None, 3, b"cable:", ["cable"], value(rng)])


def overrides(rng):
    if rng.random() < 0.1:
        return rng.choice([[("a", 1)], "cable.length=3", 7, value(rng)])
    out = {rng.choice(KEYS): value(rng) for _ in range(rng.randrange(4))}
    if rng.random() < 0.2:
        out[rng.choice([1, None, ("a",), b"cable.length"])] = 1
    return out


def capped(over):
    """The overrides with the run's duration capped (given last, it wins)."""
    out = dict(over) if isinstance(over, dict) else over
    if isinstance(out, dict):
        out.pop("simulation.duration", None)
        out["simulation.duration"] = 0.2
    return out


EXPECTED = (towsim.ScenarioError, towsim.SimulationError, TypeError, ValueError)


def call(rng, tmp, executor):
    """One input through one entry point; returns (description, exception or None)."""
    sc, over = scenario(rng, tmp), overrides(rng)
    which = rng.randrange(10)
    try:
        if which < 5:
            towsim.run(sc, capped(over))
        elif which < 9:
            depth = rng.choice([None, None, 5.0, -1, math.nan, "x", 1e300])
            towsim.statics(sc, over if rng.random() < 0.5 else None, depth)
        else:
            towsim.sweep([(sc, capped(over)), (copy.deepcopy(BASE), capped(overrides(rng)))], executor=executor,
                         frame=False)
    except EXPECTED:
        return None
    except Exception as e:  # pylint: disable=broad-except  # a finding
        return sc, over, which, e
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--seconds", type=float, default=60)
    ap.add_argument("--repro", default="fuzz_python-finding.txt")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    np.seterr(all="ignore")
    start = time.monotonic()
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(1) as executor:
        n = 0
        while n < a.runs and time.monotonic() - start < a.seconds:
            n += 1
            finding = call(rng, tmp, executor)
            if finding is not None:
                sc, over, which, e = finding
                text = (f"input {n} (seed {a.seed}), entry {['run', 'statics', 'sweep'][min(which // 5, 2)]}\n"
                        f"scenario: {sc!r}\noverrides: {over!r}\n{type(e).__name__}: {e}\n")
                with open(a.repro, "w", encoding="utf-8", errors="backslashreplace") as f:
                    f.write(text)
                print("fuzz_python: FINDING\n" + text, file=sys.stderr)
                return 1
    print(f"fuzz_python: {n} inputs in {time.monotonic() - start:.1f} s, seed {a.seed}: no finding")
    return 0


if __name__ == "__main__":
    sys.exit(main())
