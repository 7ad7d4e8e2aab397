# SPDX-License-Identifier: MIT
"""The notebook-style example runs as documented and draws its figure."""
import os
import pathlib
import subprocess
import sys


def test_the_example_runs_and_makes_its_figure(tmp_path):
    root = pathlib.Path(__file__).parents[2]
    figure = tmp_path / "example.png"
    r = subprocess.run([sys.executable, str(root / "docs/python/example.py"), str(figure)],
                       cwd=root, capture_output=True, text=True, timeout=600, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    assert "residual 0.0 m3" in r.stdout
    assert figure.stat().st_size > 10_000
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
