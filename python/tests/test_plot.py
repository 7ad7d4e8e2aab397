# SPDX-License-Identifier: MIT
"""runnel.plot (`python -m runnel plot OUT`, `runnel-plot OUT`): the figures drawn from what a command
wrote, PNG and PDF in its figures/ folder, each line the data's own; a folder no command wrote is refused with
the files it needs (exit 2)."""
import csv
import subprocess
import sys

import pytest

from conftest import RUNNEL_BINARY

pytest.importorskip("matplotlib", reason="Matplotlib is not installed (the plot extra)")
import runnel.plot  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_a_comparison_is_drawn_from_its_own_tables(tmp_path):
    out = tmp_path / "compare"
    r = subprocess.run([RUNNEL_BINARY, "compare", "--models", "pipe,thermal", "--set", "terrain.size=33", "--set",
                        "run.sim_time=5", "--set", "run.outflow_every=0.5", "--quiet", "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    figures = runnel.plot.plot(out)
    assert set(figures) == {"hydrograph", "volumes"}
    for name in figures:
        for extension in ("png", "pdf"):
            assert (out / "figures" / f"{name}.{extension}").stat().st_size > 1000
    # The pipe model's line is its outflow.csv; the bars are metrics.csv's volumes.
    table = rows(out / "pipe" / "outflow.csv")
    line = figures["hydrograph"].axes[0].get_lines()[0]
    assert list(line.get_xdata()) == [float(r["t"]) for r in table]
    assert list(line.get_ydata()) == [float(r["outflow"]) for r in table]
    metrics = rows(out / "metrics.csv")
    eroded = [bar.get_height() for bar in figures["volumes"].axes[0].containers[0]]
    assert eroded == [float(m["eroded_volume_m3"]) for m in metrics]


def test_the_hydrostatic_tank_is_drawn_beside_rho0_g_d(tmp_path):
    (tmp_path / "pressure.csv").write_text("depth,pressure,expected,particles\n0.1,990,981,40\n0.2,1950,1962,40\n")
    figures = runnel.plot.plot(tmp_path, formats=("svg",))
    expected, simulated = figures["pressure"].axes[0].get_lines()
    assert list(expected.get_ydata()) == [981, 1962] and list(simulated.get_ydata()) == [990, 1950]
    assert (tmp_path / "figures" / "pressure.svg").is_file()


def test_a_folder_no_command_wrote_is_refused_with_the_files_it_needs(tmp_path):
    r = subprocess.run([sys.executable, "-m", "runnel", "plot", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "metrics.csv" in r.stderr and "pressure.csv" in r.stderr, r.stderr
    assert not list(tmp_path.iterdir()), "nothing written"


def test_the_overland_case_is_drawn_beside_the_kinematic_wave(tmp_path):
    import json

    out = tmp_path / "overland"
    r = subprocess.run([RUNNEL_BINARY, "validate", "overland", "--models", "godunov", "--length", "20", "--rain",
                        "80000", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    case = json.loads((out / "overland.json").read_text())
    plane = runnel.plot.KinematicPlane(case["length_m"], case["slope"], case["manning_n"], case["rain_mm_h"],
                                       case["rain_duration_s"])
    # The analytic curves are the C++ scorer's: the same t_e; and after the rain the water that leaves is
    # the water the sheet held, (5/8) L h(L) per unit width.
    assert plane.equilibrium_time() == pytest.approx(case["equilibrium_time_s"], rel=1e-12)
    assert plane.outflow_share(plane.equilibrium_time()) == pytest.approx(1.0, rel=1e-9)
    a, i, length = plane.alpha, plane.rain, plane.length

    def arrival(h):  # when the characteristic of depth h reaches the foot after the rain
        return plane.duration + (length - a * h ** (5 / 3) / i) / (5 / 3 * a * h ** (2 / 3))

    h_half = 0.5 * plane.depth(length)
    assert plane.outflow_share(arrival(h_half)) == pytest.approx(a * h_half ** (5 / 3) / (i * length), rel=1e-9)
    hs = [plane.depth(length) * (1 - k / 20000) ** 3 for k in range(20000)]
    after = sum(0.5 * a * (h0 ** (5 / 3) + h1 ** (5 / 3)) * (arrival(h1) - arrival(h0)) for h0, h1 in zip(hs, hs[1:]))
    stored = 5.0 / 8.0 * length * plane.depth(length)
    assert after == pytest.approx(stored, rel=1e-3)
    figures = runnel.plot.plot(out)
    assert set(figures) == {"hydrograph", "profile"}
    model, analytic = figures["hydrograph"].axes[0].get_lines()
    assert model.get_label() == "godunov" and analytic.get_label() == "kinematic wave"
    gauges = figures["profile"].axes[0].get_lines()[1]
    assert list(gauges.get_ydata()) == [g["depth_m"] for g in case["runs"][0]["gauges"]]
