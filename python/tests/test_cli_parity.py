# SPDX-License-Identifier: MIT
"""Python and the CLI give the same result, bit for bit, for the same scenario."""
import json

import numpy as np
import pytest

import runnel

SCENARIOS = {
    "pipe": """
[run]
model = "pipe"
steps = 40
seed = 5
[terrain]
generator = "fbm"
size = 65
cell = 2.0
[pipe]
rain = 0.02
""",
    "sph": """
[run]
model = "sph"
steps = 60
seed = 3
[terrain]
generator = "fbm"
size = 33
cell = 1.0
""",
    "droplet": """
[run]
model = "droplet"
steps = 4
seed = 9
[terrain]
generator = "fbm"
size = 65
""",
}


@pytest.mark.parametrize("name", sorted(SCENARIOS))
def test_python_steps_equal_the_cli_run(name, scenario, run_cli, tmp_path):
    path = scenario(SCENARIOS[name])
    out = tmp_path / "cli"
    r = run_cli("run", path, "--out", out, "--quiet")
    assert r.returncode == 0, r.stderr
    cli_final = np.load(out / "final.npy")
    cli_metrics = json.loads((out / "metrics.json").read_text())

    model = runnel.Model.from_scenario(str(path))
    for _ in range(cli_metrics["steps"]):
        model.step()
    heights = model.terrain().heights
    assert heights.shape == cli_final.shape
    assert np.array_equal(heights, cli_final), "bit for bit"
    assert model.time == cli_metrics["sim_time"]
    assert model.mass_balance()["residual"] == 0.0


def test_run_writes_what_the_cli_writes(scenario, run_cli, tmp_path):
    path = scenario(SCENARIOS["pipe"])
    r = run_cli("run", path, "--out", tmp_path / "cli", "--quiet")
    assert r.returncode == 0, r.stderr
    metrics = runnel.Model.from_scenario(str(path)).run(str(tmp_path / "py"))
    assert isinstance(metrics, dict), "run() returns metrics.json's contents"
    assert metrics["steps"] == 40
    for name in ("final.npy", "final.asc", "final.tif", "erosion.tif"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
