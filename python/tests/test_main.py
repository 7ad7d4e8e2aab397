# SPDX-License-Identifier: MIT
"""`python -m runnel` runs the command-line tool installed with the package."""
import subprocess
import sys

import runnel


def test_python_m_runnel_runs_the_installed_command_line_tool():
    done = subprocess.run([sys.executable, "-m", "runnel", "--version"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("runnel " + runnel.__version__), done.stdout


def test_python_m_runnel_passes_the_exit_code_of_a_refused_command():
    done = subprocess.run(
        [sys.executable, "-m", "runnel", "run", "--set", "no.such_key=1"], capture_output=True, text=True
    )
    assert done.returncode == 2
    assert "no.such_key" in done.stderr
