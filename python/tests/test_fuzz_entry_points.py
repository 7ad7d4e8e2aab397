# SPDX-License-Identifier: MIT
"""A fuzzing harness for the Python entry points: seeded random arguments (shapes, dtypes,
non-finite values, sizes that do not match, wrong types, random files) thrown at every function
and method. Each call must return or raise runnel.InputError, TypeError or ValueError; a crash
kills the interpreter and fails the suite. RUNNEL_FUZZ_ITERATIONS runs it longer (scripts/fuzz.sh)."""
import os

import numpy as np
import pytest

import runnel

ITERATIONS = int(os.environ.get("RUNNEL_FUZZ_ITERATIONS", "2000"))
EXPECTED = (runnel.InputError, TypeError, ValueError, OverflowError)


def _number(rng):
    return rng.choice([0.0, -1.0, 1.0, 1e-300, 1e300, float("nan"), float("inf"), -float("inf"),
                       2.0 ** 63, rng.normal() * 10 ** rng.integers(0, 12), 7, -7, 0])


def _array(rng):
    ndim = int(rng.integers(0, 4))
    shape = tuple(int(rng.choice([0, 1, 2, 3, 9, 17])) for _ in range(ndim))
    dtype = [np.float32, np.float64, np.int64, np.uint8, np.bool_][int(rng.integers(0, 5))]
    a = (rng.normal(size=shape) * 10 ** rng.integers(0, 8)).astype(dtype)
    if a.size and rng.random() < 0.3:
        a.flat[int(rng.integers(0, a.size))] = np.nan if a.dtype.kind == "f" else 0
    return a if rng.random() < 0.8 else ["heights", None, 3, [1, 2]][int(rng.integers(0, 4))]


def _terrain(rng):
    try:
        return runnel.Terrain(_array(rng), cell=_number(rng))
    except EXPECTED:
        return runnel.Terrain(np.zeros((9, 9), dtype=np.float32), cell=1.0)


def _call(function, *args, **kwargs):
    try:
        function(*args, **kwargs)
    except EXPECTED:
        pass


def test_random_arguments_are_refused_or_taken_never_a_crash(tmp_path):
    rng = np.random.default_rng(20261206)
    base = runnel.Terrain(rng.random((9, 9)).astype(np.float32), cell=1.0)
    models = {name: runnel.Model(name, base) for name in ("thermal", "pipe", "olsen")}
    names = ["thermal", "pipe", "olsen", "droplet", "stream-power", "sph", "", "x" * 300, "\x1b[2J"]
    keys = ["thermal.rate", "pipe.rain", "run.seed", "terrain.cell", "no.such", "rain.rate", ""]
    for k in range(ITERATIONS):
        choice = k % 9
        if choice == 0:
            _call(runnel.Terrain, _array(rng), cell=_number(rng))
        elif choice == 1:
            t = _terrain(rng)
            for attribute in ("cell", "origin_x", "origin_z"):
                _call(setattr, t, attribute, _number(rng))
            assert np.isfinite(t.cell) and t.cell > 0
        elif choice == 2:
            _call(runnel.terrain_metrics, _terrain(rng), _terrain(rng))
        elif choice == 3:
            params = {str(rng.choice(keys)): _number(rng) for _ in range(int(rng.integers(0, 3)))}
            _call(runnel.Model, str(rng.choice(names[:3] + names[6:])), _terrain(rng), params)
        elif choice == 4:
            name = str(rng.choice(list(models)))
            model = models[name]
            # Refused (not finite, negative, beyond 1e12) or a few steps: a valid huge dt would
            # simply run that long.
            bad = [float("nan"), float("inf"), -1.0, -1e-300, 1e300, 2.0 ** 63, 1.5e12]
            try:
                _call(model.advance, bad[int(rng.integers(0, len(bad)))] if rng.random() < 0.7
                      else float(rng.integers(0, 3)))
            except runnel.RunnelRuntimeError:
                # A state set_field made absurd (metres of water a cell) may collapse the time
                # step: a clear stop, as it must be. The next iterations get a fresh model.
                models[name] = runnel.Model(name, base)
        elif choice == 5:
            model = models[str(rng.choice(list(models)))]
            names_here = model.field_names() + ["no_such_field", ""]
            name = str(rng.choice(names_here))
            _call(model.field, name)
            _call(model.set_field, name, _array(rng))
        elif choice == 6:
            path = tmp_path / f"random{k}.{rng.choice(['asc', 'npy', 'png', 'tif', 'h5', 'toml'])}"
            path.write_bytes(rng.bytes(int(rng.integers(0, 400))))
            _call(runnel.read_terrain, str(path))
            _call(runnel.Model.load_checkpoint, str(path))
            _call(runnel.Model.from_scenario, str(path))
        elif choice == 7:
            _call(runnel.generate, str(rng.choice(["fbm", "plane", "nope"])),
                  int(rng.choice([0, 1, 2, 17, -5])), int(rng.choice([0, 2, 17])),
                  _number(rng), int(rng.integers(0, 2 ** 31)))
        else:
            _call(runnel.write_terrain, str(tmp_path / f"w{k}.{rng.choice(['asc', 'npy', 'x'])}"),
                  _terrain(rng))
    for model in models.values():  # the models are still usable
        model.advance(1)
        assert np.all(np.isfinite(model.terrain().heights))
