# SPDX-License-Identifier: MIT
"""Shared fixtures: the runnel binary (for CLI parity) and scratch scenarios."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("RUNNEL_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
RUNNEL_BINARY = os.environ.get("RUNNEL_BINARY", str(SOURCE_DIR / "build" / "runnel"))


@pytest.fixture
def run_cli():
    """Runs the runnel binary; returns the CompletedProcess (text)."""

    def run(*args):
        return subprocess.run([RUNNEL_BINARY, *map(str, args)], capture_output=True, text=True)

    return run


@pytest.fixture
def scenario(tmp_path):
    """Writes a scenario TOML file and returns its path."""

    def write(text, name="scenario.toml"):
        path = tmp_path / name
        path.write_text(text)
        return path

    return write
