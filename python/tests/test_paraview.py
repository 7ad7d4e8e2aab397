# SPDX-License-Identifier: MIT
"""The ParaView-ready outputs, read back by independent readers and compared with the checkpoint:
series.xmf (resolved here from its XML and series.h5 with h5py, the way an XDMF reader does; ParaView's
own readers are in test_paraview_readers.py), and the PLY particle frame (VTK's vtkPLYReader and meshio)."""
import json
import shutil
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

h5py = pytest.importorskip("h5py", reason="h5py is not installed (python3-h5py)")

SPH = """
[run]
model = "sph"
steps = 60
seed = 4
[terrain]
generator = "fbm"
size = 33
cell = 1.0
"""


@pytest.fixture(scope="module")
def sph_run(tmp_path_factory):
    from conftest import RUNNEL_BINARY
    import subprocess

    out = tmp_path_factory.mktemp("sph")
    (out / "s.toml").write_text(SPH)
    r = subprocess.run([RUNNEL_BINARY, "run", str(out / "s.toml"), "--out", str(out / "run"), "--quiet",
                        "--series-every", "20", "--particles-every", "30"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return out / "run"


def resolve(item, folder):
    """The array an XDMF DataItem stands for."""
    if item.get("ItemType") == "HyperSlab":
        selection, source = list(item)
        start, stride, count = np.array(selection.text.split(), dtype=int).reshape(3, -1)
        data = resolve(source, folder)
        index = tuple(slice(s, s + c * t, t) for s, t, c in zip(start, stride, count))
        return data[index].reshape([int(d) for d in item.get("Dimensions").split()])
    assert item.get("Format") == "HDF"
    name, path = item.text.strip().split(":")
    with h5py.File(folder / name, "r") as f:
        data = f[path][()]
    assert list(data.shape) == [int(d) for d in item.get("Dimensions").split()], path
    return data


def grids(folder, collection):
    root = ET.parse(folder / "series.xmf").getroot()
    for grid in root.iter("Grid"):
        if grid.get("Name") == collection and grid.get("CollectionType") == "Temporal":
            return [(float(g.find("Time").get("Value")), g) for g in grid.findall("Grid")]
    return []


def test_the_terrain_series_is_the_runs_heightmaps(sph_run):
    frames = grids(sph_run, "terrain")
    assert len(frames) == 4, "the start (step 0) and steps 20, 40 and 60"
    with h5py.File(sph_run / "final.h5", "r") as f:
        final = f["/terrain/height"][()]
        time = f["/state"].attrs["time"] if "time" in f["/state"].attrs else None
        cell = f["/terrain"].attrs["cell"]
    (t_first, first), (t_last, last) = frames[0], frames[-1]
    assert t_first == 0.0, "the series starts from the initial state"
    points = resolve(last.find("Geometry")[0], sph_run)
    ny, nx = final.shape
    assert points.shape == (nx * ny, 3)
    assert np.array_equal(points[:, 2].reshape(ny, nx), final), "the last frame is the final terrain"
    attributes = {a.get("Name"): resolve(a[0], sph_run) for a in last.findall("Attribute")}
    assert np.array_equal(attributes["height"], final)
    x, y = points[:, 0].reshape(ny, nx), points[:, 1].reshape(ny, nx)
    assert x[0, 1] - x[0, 0] == cell and y[0, 0] - y[1, 0] == cell, "x east, y north"
    with h5py.File(sph_run / "series.h5", "r") as f:
        initial = f["/height"][0]
    assert np.allclose(attributes["dh"], final - initial, atol=1e-6), "Δh from the initial terrain"
    assert "depth" in attributes, "the water binned onto the vertices"
    quads = resolve(last.find("Topology")[0], sph_run)
    assert quads.shape == ((nx - 1) * (ny - 1), 4) and quads.max() == nx * ny - 1
    if time is not None:
        assert t_last == pytest.approx(time)
    assert [t for t, _ in frames] == sorted(t for t, _ in frames)


def test_the_particle_snapshots_match_the_checkpoint_and_keep_their_ids(sph_run):
    frames = grids(sph_run, "particles")
    assert len(frames) == 2, "steps 30 and 60"
    with h5py.File(sph_run / "final.h5", "r") as f:
        p = {k: f["/particles/" + k][()] for k in ("x", "y", "z", "vx", "vy", "vz", "id", "age", "rho")}
        ny = f["/terrain/height"].shape[0]
        cell = f["/terrain"].attrs["cell"]
    _, last = frames[-1]
    position = resolve(last.find("Geometry")[0], sph_run)
    attributes = {a.get("Name"): resolve(a[0], sph_run) for a in last.findall("Attribute")}
    # The map frame: column 0 and row 0 at their pixels' centres, half a cell inside the raster's
    # corner (here at the map's origin).
    west, north = 0.5 * cell, (ny - 0.5) * cell
    assert np.array_equal(position[:, 0], west + p["x"].astype(np.float64))
    assert np.array_equal(position[:, 1], north - p["z"].astype(np.float64))
    assert np.array_equal(position[:, 2], p["y"].astype(np.float64))
    assert np.array_equal(attributes["id"], p["id"] & 0x7FFFFFFF)
    assert np.array_equal(attributes["density"], p["rho"])
    assert np.array_equal(attributes["velocity"][:, 1], -p["vz"])
    # Stable ids: a particle of the first snapshot alive in the last is older by the time between.
    (t0, first), (t1, _) = frames
    ids0 = resolve(first.find("Attribute[@Name='id']")[0], sph_run)
    age0 = resolve(first.find("Attribute[@Name='age']")[0], sph_run)
    common, i0, i1 = np.intersect1d(ids0, attributes["id"], return_indices=True)
    assert len(common) > 10
    assert np.allclose(attributes["age"][i1] - age0[i0], t1 - t0, rtol=1e-4, atol=1e-4)


def test_the_ply_frame_is_the_checkpoints_particles(sph_run, run_cli):
    vtk = pytest.importorskip("vtk", reason="VTK's Python module is not installed (python3-vtk9)")
    meshio = pytest.importorskip("meshio", reason="meshio is not installed (python3-meshio)")
    r = run_cli("export", sph_run / "final.h5", "--format", "ply", "-o", sph_run / "particles.ply")
    assert r.returncode == 0, r.stderr
    with h5py.File(sph_run / "final.h5", "r") as f:
        x, y, z = (f["/particles/" + k][()] for k in ("x", "y", "z"))
        ids = f["/particles/id"][()] & 0x7FFFFFFF
        cell = f["/terrain"].attrs["cell"]
        west, north = 0.5 * cell, (f["/terrain/height"].shape[0] - 0.5) * cell
    reader = vtk.vtkPLYReader()
    reader.SetFileName(str(sph_run / "particles.ply"))
    reader.Update()
    points = reader.GetOutput().GetPoints()
    assert points.GetNumberOfPoints() == len(x)
    got = np.array([points.GetPoint(k) for k in range(len(x))])
    assert np.allclose(got, np.stack([west + x, north - z, y], axis=1), atol=1e-5)
    mesh = meshio.read(sph_run / "particles.ply")
    assert np.array_equal(mesh.point_data["id"], ids)
    assert set(mesh.point_data) >= {"vx", "vy", "vz", "density", "sediment", "age", "id"}


def test_the_vtp_frame_opens_in_paraview_with_its_cells_and_fields(sph_run, run_cli, tmp_path):
    # ParaView's default reader for .vtp (XMLPolyDataReader) in pvpython: a vertex cell per particle
    # and every field; positions and ids those of the checkpoint in the map frame. (Its PLY reader
    # reads the positions only, no cells and none of the other properties.)
    pvpython = shutil.which("pvpython")
    if pvpython is None:
        pytest.skip("ParaView's pvpython is not installed (scripts/setup.sh)")
    r = run_cli("export", sph_run / "final.h5", "--format", "vtp", "-o", sph_run / "particles.vtp")
    assert r.returncode == 0, r.stderr
    script = tmp_path / "read_vtp.py"
    script.write_text(
        "import json, sys\n"
        "from paraview import simple, servermanager\n"
        "from vtkmodules.util.numpy_support import vtk_to_numpy\n"
        "reader = simple.OpenDataFile(sys.argv[1])\n"
        "reader.UpdatePipeline()\n"
        "data = servermanager.Fetch(reader)\n"
        "pd = data.GetPointData()\n"
        "print(json.dumps({'reader': reader.GetXMLName(), 'cells': data.GetNumberOfVerts(),\n"
        "    'points': vtk_to_numpy(data.GetPoints().GetData()).tolist(),\n"
        "    'id': vtk_to_numpy(pd.GetArray('id')).tolist(),\n"
        "    'arrays': {pd.GetArrayName(i): pd.GetArray(i).GetNumberOfComponents()\n"
        "               for i in range(pd.GetNumberOfArrays())}}))\n")
    r = subprocess.run([pvpython, str(script), str(sph_run / "particles.vtp")], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    got = json.loads(r.stdout.strip().splitlines()[-1])
    with h5py.File(sph_run / "final.h5", "r") as f:
        x, y, z = (f["/particles/" + k][()] for k in ("x", "y", "z"))
        ids = f["/particles/id"][()] & 0x7FFFFFFF
        cell = f["/terrain"].attrs["cell"]
        west, north = 0.5 * cell, (f["/terrain/height"].shape[0] - 0.5) * cell
    assert got["reader"] == "XMLPolyDataReader"
    assert got["cells"] == len(x) > 0
    assert got["arrays"] == {"velocity": 3, "density": 1, "sediment": 1, "age": 1, "id": 1}
    assert np.array_equal(np.array(got["points"]), np.stack([west + x.astype(np.float64), north - z.astype(np.float64),
                                                             y.astype(np.float64)], axis=1))
    assert np.array_equal(got["id"], ids)


def test_a_particle_export_is_named_for_its_format(sph_run, run_cli):
    target = sph_run / "named_wrong.ply"
    target.write_bytes(b"kept")
    r = run_cli("export", sph_run / "final.h5", "--format", "vtp", "-o", target)
    assert r.returncode == 2
    assert "named_wrong.ply" in r.stderr and ".vtp" in r.stderr and r.stderr.count("\n") == 1
    assert target.read_bytes() == b"kept"


def test_particles_every_is_refused_for_a_grid_model(run_cli, tmp_path):
    r = run_cli("run", "--model", "pipe", "--steps", "5", "--particles-every", "2", "--out", tmp_path / "o")
    assert r.returncode == 2
    assert "--particles-every" in r.stderr and r.stderr.count("\n") == 1
