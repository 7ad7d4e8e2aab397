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


def test_the_dam_break_front_is_drawn_beside_each_reference_it_is_judged_against(tmp_path):
    (tmp_path / "front.csv").write_text("t_star,x_over_L\n0,1\n0.5,1.4\n1,1.9\n")
    (tmp_path / "front_reference.csv").write_text(
        "source,t_star,x_over_L\nKoshizuka & Oka 1996,0.4,1.3\nKoshizuka & Oka 1996,0.9,1.8\n"
        '"Koshizuka & Oka 1996, read again (PySPH)",0.45,1.31\n'
        '"PySPH, the same instant release, 67 across l",0.5,1.45\n')
    figures = runnel.plot.plot(tmp_path, formats=("png",))
    lines = {line.get_label(): line for line in figures["front"].axes[0].get_lines()}
    assert list(lines["Koshizuka & Oka 1996"].get_ydata()) == [1.3, 1.8]
    assert list(lines["Koshizuka & Oka 1996, read again (PySPH)"].get_xdata()) == [0.45]
    assert list(lines["PySPH, the same instant release, 67 across l"].get_ydata()) == [1.45]
    assert list(lines["runnel"].get_ydata()) == [1, 1.4, 1.9]


def test_the_mobile_bed_flume_is_drawn_beside_the_measurements(tmp_path):
    out = tmp_path / "flume"
    r = subprocess.run([RUNNEL_BINARY, "validate", "mobile-bed", "--resolution", "5", "--models", "pipe", "--out",
                        str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    figures = runnel.plot.plot(out, formats=("png",))
    assert set(figures) == {"gauges", "profiles"}
    table = rows(out / "pipe" / "gauges.csv")
    first = figures["gauges"].axes[0]
    lines = {line.get_label(): line for line in first.get_lines()}
    measured = [float(r["surface"]) for r in table if r["gauge"] == "G1" and r["source"] == "measured"]
    simulated = [float(r["surface"]) for r in table if r["gauge"] == "G1" and r["source"] == "pipe"]
    assert measured and list(lines["measured"].get_ydata()) == measured
    assert simulated and list(lines["pipe"].get_ydata()) == simulated
    assert [a.get_title() for a in figures["gauges"].axes] == ["G1", "G2", "G3", "G4"]
    bed = rows(out / "pipe" / "profiles.csv")
    s1 = [float(r["simulated"]) for r in bed if r["profile"] == bed[0]["profile"]]
    assert list(figures["profiles"].axes[0].get_lines()[-1].get_ydata()) == s1
    # A flume folder without its profiles is refused by name.
    (out / "pipe" / "profiles.csv").unlink()
    with pytest.raises(runnel.InputError, match="profiles.csv"):
        runnel.plot.plot(out)


def test_a_sweep_draws_each_metric_against_each_numeric_parameter_per_model(tmp_path):
    (tmp_path / "base.toml").write_text('[run]\nmodel = "pipe"\nsteps = 10\n[terrain]\nsize = 33\n')
    (tmp_path / "sweep.toml").write_text(
        '[sweep]\nbase = "base.toml"\nmetrics = ["eroded_volume"]\n[axes]\nmodel = ["pipe", "olsen"]\n'
        '"rain.intensity" = [2000.0, 60000.0]\nseed = [1, 2]\n')
    out = tmp_path / "out"
    r = subprocess.run([RUNNEL_BINARY, "sweep", str(tmp_path / "sweep.toml"), "--out", str(out), "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    figures = runnel.plot.plot(out, formats=("png",))
    assert set(figures) == {"eroded_volume_vs_rain.intensity", "eroded_volume_vs_run.seed"}
    results = rows(out / "results.csv")
    lines = {line.get_label(): line for line in figures["eroded_volume_vs_rain.intensity"].axes[0].get_lines()}
    assert set(lines) == {"pipe", "olsen"}
    for model, line in lines.items():
        assert list(line.get_xdata()) == [2000.0, 60000.0]
        for x, y in zip(line.get_xdata(), line.get_ydata()):
            members = [float(m["eroded_volume"]) for m in results
                       if m["run.model"] == model and float(m["rain.intensity"]) == x]
            assert len(members) == 2 and y == pytest.approx(sum(members) / 2, rel=1e-12)
