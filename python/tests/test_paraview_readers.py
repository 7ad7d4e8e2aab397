# SPDX-License-Identifier: MIT
"""ParaView itself opens the series: pvpython (Debian's paraview) reads series.xmf with its default
XDMF3 reader and with the legacy XDMF reader, and finds every frame's points and fields, the first
frame at t = 0 and the last at the run's end, for a grid model (water depth, velocity, Δh) and SPH."""
import contextlib
import json
import os
import shutil
import subprocess

import pytest

from conftest import RUNNEL_BINARY

PVPYTHON = shutil.which("pvpython")
pytestmark = pytest.mark.skipif(PVPYTHON is None, reason="ParaView's pvpython is not installed (scripts/setup.sh)")

# Runs inside pvpython: every time step through each reader, as ParaView's GUI would load them.
READ = r"""
import json, sys
from paraview import simple, servermanager
out = {}
for name, make in (("xdmf3", lambda f: simple.Xdmf3ReaderS(FileName=[f])),
                   ("legacy", lambda f: simple.XDMFReader(FileNames=[f]))):
    reader = make(sys.argv[1])
    frames = []
    for t in reader.TimestepValues:
        reader.UpdatePipeline(time=t)
        data = servermanager.Fetch(reader)
        if data.IsA("vtkMultiBlockDataSet"):
            data = data.GetBlock(0)
        point_data = data.GetPointData()
        arrays = [point_data.GetArrayName(i) for i in range(point_data.GetNumberOfArrays())]
        frames.append({"time": t, "points": data.GetNumberOfPoints(), "arrays": arrays})
    out[name] = frames
print(json.dumps(out))
"""


def read_with_paraview(xmf, tmp_path):
    script = tmp_path / "read.py"
    script.write_text(READ)
    r = subprocess.run([PVPYTHON, str(script), str(xmf)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    return json.loads(r.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("model, fields", [("pipe", {"height", "dh", "depth", "speed", "velocity"}),
                                           ("sph", {"height", "dh", "depth", "speed", "velocity"})])
def test_paraview_reads_every_frame_with_both_readers(tmp_path, model, fields):
    out = tmp_path / "run"
    r = subprocess.run([RUNNEL_BINARY, "run", "--generate", "fbm", "--set", "terrain.size=33", "--model", model,
                        "--set", "run.steps=7", "--series-every", "3", "--quiet", "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    end = json.loads((out / "metrics.json").read_text())["sim_time"]
    frames = read_with_paraview(out / "series.xmf", tmp_path)
    for reader in ("xdmf3", "legacy"):
        got = frames[reader]
        assert [f["time"] for f in got][0] == 0.0, f"{reader}: the first frame is t = 0"
        assert got[-1]["time"] == pytest.approx(end), f"{reader}: the last frame is the run's end"
        assert len(got) == 4, f"{reader}: steps 0, 3, 6 and 7"
        for f in got:
            assert f["points"] == 33 * 33, f"{reader} at t = {f['time']}"
            assert fields <= set(f["arrays"]), f"{reader} at t = {f['time']}: {f['arrays']}"


# Runs inside pvpython under Xvfb: the last particle frame drawn red on white in each representation,
# through the default XDMF3 reader, and the red pixels counted.
DRAW = r"""
import json, sys
from paraview import simple
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy
reader = simple.Xdmf3ReaderS(FileName=[sys.argv[1]])
view = simple.CreateRenderView()
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 0
view.ViewTime = reader.TimestepValues[-1]
shown = simple.Show(reader, view)
shown.ColorArrayName = ["POINTS", ""]
shown.AmbientColor = shown.DiffuseColor = [1, 0, 0]
shown.PointSize = 6
view.ResetCamera()
red = {}
for representation in ("Points", "Surface", "Point Gaussian"):
    shown.SetRepresentationType(representation)
    path = sys.argv[2] + "/" + representation.replace(" ", "_") + ".png"
    simple.SaveScreenshot(path, view, ImageResolution=[400, 300])
    png = vtkPNGReader()
    png.SetFileName(path)
    png.Update()
    image = png.GetOutput()
    rgb = vtk_to_numpy(image.GetPointData().GetScalars())
    red[representation] = int(((rgb[:, 0] > 128) & (rgb[:, 1] < 80) & (rgb[:, 2] < 80)).sum())
print(json.dumps(red))
"""


@contextlib.contextmanager
def x_server():
    """An Xvfb server of our own, used once it says it is ready: -displayfd writes the display's number
    when the server accepts clients (xvfb-run -a waits a fixed time, and on a busy machine pvpython
    connected before the server was up and aborted)."""
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", "1280x900x24", "-nolisten", "tcp",
                               "-noreset"], pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as ready:
        number = ready.readline().strip()
    try:
        assert number, "Xvfb did not start"
        yield ":" + number
    finally:
        server.terminate()
        server.wait(timeout=60)


@pytest.mark.skipif(shutil.which("Xvfb") is None, reason="Xvfb is not installed (scripts/setup.sh)")
def test_paraview_draws_the_particles_in_every_representation(tmp_path):
    # The particles alone (no terrain frames): every red pixel is a particle. Each particle is a vertex
    # cell of its own; a point set without cells reads as points but draws nothing in Points and Surface.
    out = tmp_path / "run"
    r = subprocess.run([RUNNEL_BINARY, "run", "--generate", "fbm", "--set", "terrain.size=33", "--set", "run.steps=30",
                        "--particles-every", "10", "--quiet", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    xmf = (out / "series.xmf").read_text()
    last = int(xmf.rsplit('NumberOfElements="', 1)[1].split('"')[0])
    assert last > 10, "the last frame holds particles"
    script = tmp_path / "draw.py"
    script.write_text(DRAW)
    with x_server() as display:
        r = subprocess.run([PVPYTHON, str(script), str(out / "series.xmf"), str(tmp_path)], capture_output=True,
                           text=True, timeout=300, env={**os.environ, "DISPLAY": display})
    assert r.returncode == 0, r.stderr[-3000:]
    red = json.loads(r.stdout.strip().splitlines()[-1])
    # Points of 6 pixels: tens of pixels each (some overlap); the Gaussian splats at least one each.
    assert red["Points"] >= 10 * last, red
    assert red["Surface"] >= 10 * last, red
    assert red["Point Gaussian"] >= last, red


# Runs inside pvpython: series.pvd through ParaView's own reader for it, every time step, each
# block's name, points, cells and arrays.
BLOCKS = r"""
import json, sys
from paraview import simple, servermanager
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet
reader = simple.OpenDataFile(sys.argv[1])
frames = []
for t in reader.TimestepValues:
    reader.UpdatePipeline(time=t)
    data = servermanager.Fetch(reader)
    blocks = {}
    for b in range(data.GetNumberOfBlocks()):
        name = data.GetMetaData(b).Get(vtkCompositeDataSet.NAME())
        piece = data.GetBlock(b).GetBlock(0)
        point_data = piece.GetPointData()
        blocks[name] = {"points": piece.GetNumberOfPoints(), "cells": piece.GetNumberOfCells(),
                        "arrays": [point_data.GetArrayName(i) for i in range(point_data.GetNumberOfArrays())]}
    frames.append({"time": t, "reader": reader.GetXMLName(), "blocks": blocks})
print(json.dumps(frames))
"""


def test_paraview_opens_the_vtk_series_as_named_terrain_and_particle_blocks(tmp_path):
    out = tmp_path / "run"
    r = subprocess.run([RUNNEL_BINARY, "run", "--generate", "fbm", "--set", "terrain.size=33", "--set", "run.steps=30",
                        "--series-every", "10", "--particles-every", "10", "--quiet", "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    script = tmp_path / "blocks.py"
    script.write_text(BLOCKS)
    r = subprocess.run([PVPYTHON, str(script), str(out / "series.pvd")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    frames = json.loads(r.stdout.strip().splitlines()[-1])
    assert [f["time"] for f in frames][0] == 0.0 and len(frames) == 4, "steps 0, 10, 20 and 30"
    end = json.loads((out / "metrics.json").read_text())["sim_time"]
    assert frames[-1]["time"] == pytest.approx(end)
    for f in frames:
        assert f["reader"] == "PVDReader"
        assert set(f["blocks"]) == {"terrain", "particles"}, f
        terrain = f["blocks"]["terrain"]
        assert terrain["points"] == 33 * 33 and terrain["cells"] == 32 * 32, f
        assert {"height", "dh", "depth", "speed", "velocity"} <= set(terrain["arrays"]), f
    last = frames[-1]["blocks"]["particles"]
    assert last["points"] > 10 and last["cells"] == last["points"], "each particle a vertex cell"
    assert {"velocity", "density", "sediment", "age", "id"} <= set(last["arrays"])
