# SPDX-License-Identifier: MIT
"""The package as `pip install .` put it into .venv (scripts/setup-python.sh), outside the tree."""
import os
import subprocess

import pytest

from conftest import SOURCE_DIR

VENV_PYTHON = SOURCE_DIR / ".venv" / "bin" / "python"
needs_venv = pytest.mark.skipif(not VENV_PYTHON.exists(),
                                reason="no .venv: scripts/setup-python.sh installs the package there")


def run_in_venv(code, cwd):
    """`code` run by the environment's python, outside the tree and without this tree's PYTHONPATH."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run([str(VENV_PYTHON), "-c", code], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=300)


@needs_venv
def test_the_pip_installed_package_imports_and_runs(tmp_path):
    code = ("import runnel, runnel.bmi\n"
            "t = runnel.generate('fbm', 33, 33, 1.0, seed=2)\n"
            "m = runnel.Model('thermal', t)\n"
            "m.advance(5)\n"
            "print(runnel.__file__)\n"
            "print(m.steps, m.mass_balance()['residual_quanta'])\n")
    r = run_in_venv(code, tmp_path)
    assert r.returncode == 0, r.stderr
    location, result = r.stdout.split("\n")[:2]
    assert "site-packages" in location and str(SOURCE_DIR / "python") not in location
    assert result == "5 0"


@needs_venv
def test_the_wheel_installs_the_distribution_its_cli_and_its_stubs(tmp_path):
    code = ("import importlib.metadata, pathlib, runnel\n"
            "print(importlib.metadata.version('runnel-erosion'))\n"
            "package = pathlib.Path(runnel.__file__).parent\n"
            "print((package / 'py.typed').exists(), (package / '_runnel.pyi').exists())\n")
    r = run_in_venv(code, tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split("\n")[:2] == [runnel_version(), "True True"]
    # The CLI among the environment's scripts, on PATH beside its python.
    cli = VENV_PYTHON.parent / "runnel"
    assert cli.exists(), "the wheel installs the runnel command into the environment's bin/"
    r = subprocess.run([str(cli), "--version"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and runnel_version() in r.stdout + r.stderr


def runnel_version():
    import runnel

    return runnel.__version__

