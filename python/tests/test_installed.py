# SPDX-License-Identifier: MIT
"""The package as `pip install .` put it into .venv (scripts/setup-python.sh), outside the tree."""
import os
import subprocess

import pytest

from conftest import SOURCE_DIR

VENV_PYTHON = SOURCE_DIR / ".venv" / "bin" / "python"


@pytest.mark.skipif(not VENV_PYTHON.exists(),
                    reason="no .venv: scripts/setup-python.sh installs the package there")
def test_the_pip_installed_package_imports_and_runs(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    code = ("import runnel, runnel.bmi\n"
            "t = runnel.generate('fbm', 33, 33, 1.0, seed=2)\n"
            "m = runnel.Model('thermal', t)\n"
            "m.advance(5)\n"
            "print(runnel.__file__)\n"
            "print(m.steps, m.mass_balance()['residual_quanta'])\n")
    r = subprocess.run([str(VENV_PYTHON), "-c", code], cwd=tmp_path, env=env, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    location, result = r.stdout.split("\n")[:2]
    assert "site-packages" in location and str(SOURCE_DIR / "python") not in location
    assert result == "5 0"
