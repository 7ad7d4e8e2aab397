# SPDX-License-Identifier: MIT
"""The cost of driving a model from Python, step by step, against the same steps inside the CLI
(metrics.json's wall_seconds, which excludes start-up). A benchmark, not a test; prints JSON.

    PYTHONPATH=build/python python3 bench/python_overhead.py [SIZE] [STEPS]
"""
import json
import pathlib
import subprocess
import sys
import tempfile
import time

import runnel

size = int(sys.argv[1]) if len(sys.argv) > 1 else 65
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
root = pathlib.Path(__file__).parents[1]
scenario = f"""
[run]
model = "thermal"
steps = {steps}
[terrain]
generator = "fbm"
size = {size}
"""
with tempfile.TemporaryDirectory() as tmp:
    path = pathlib.Path(tmp) / "s.toml"
    path.write_text(scenario)
    subprocess.run([str(root / "build/runnel"), "run", str(path), "--out", tmp + "/cli", "--quiet"], check=True)
    cli = json.loads((pathlib.Path(tmp) / "cli/metrics.json").read_text())["wall_seconds"]
    model = runnel.Model.from_scenario(str(path))
    model.step()  # kernels built and warm, as in the CLI run
    start = time.perf_counter()
    for _ in range(steps):
        model.step()
    model.mass_balance()  # waits for the device, as the CLI's end does
    python = time.perf_counter() - start
print(json.dumps({"benchmark": "python_overhead", "model": "thermal", "size": size, "steps": steps,
                  "cli_seconds": cli, "python_seconds": python,
                  "overhead_per_step_us": (python - cli) / steps * 1e6,
                  "cli_per_step_us": cli / steps * 1e6}))
