# SPDX-License-Identifier: MIT
"""The tutorial's notebooks (docs/notebooks/) run from top to bottom in a fresh kernel (nbclient), in a
scratch folder, with the runnel CLI on PATH as a wheel puts it and Jupyter's default plotting backend,
and each figure they draw comes out as a picture."""
import os
import pathlib

import pytest

from conftest import RUNNEL_BINARY, SOURCE_DIR

nbformat = pytest.importorskip("nbformat", reason="nbformat is not installed (scripts/setup-python.sh)")
nbclient = pytest.importorskip("nbclient", reason="nbclient is not installed (scripts/setup-python.sh)")

NOTEBOOKS = sorted((SOURCE_DIR / "docs" / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_the_notebook_runs(path, tmp_path, monkeypatch):
    for module in ("landlab", "xarray", "osgeo.gdal", "matplotlib"):
        pytest.importorskip(module, reason=f"{module} is not installed (scripts/setup-python.sh)")
    # The kernel inherits the environment: the package under test, the CLI beside it, the data.
    monkeypatch.setenv("PATH", str(pathlib.Path(RUNNEL_BINARY).resolve().parent) + os.pathsep + os.environ["PATH"])
    monkeypatch.setenv("RUNNEL_SOURCE_DIR", str(SOURCE_DIR))
    # Jupyter's own backend (inline), as a user's kernel has it: not the suite's Agg.
    monkeypatch.delenv("MPLBACKEND", raising=False)
    notebook = nbformat.read(path, as_version=4)
    nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    errors = [o for cell in notebook.cells for o in cell.get("outputs", []) if o.output_type == "error"]
    assert not errors
    # Every cell that draws a figure shows it, as a PNG in its outputs.
    drawing = [cell for cell in notebook.cells if cell.cell_type == "code" and "plt." in cell.source]
    assert drawing, "the notebook draws no figure"
    for cell in drawing:
        pictures = [o for o in cell.get("outputs", []) if "image/png" in o.get("data", {})]
        assert pictures, "a figure cell shows no picture:\n" + cell.source
