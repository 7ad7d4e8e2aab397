# SPDX-License-Identifier: MIT
"""Figures for papers from the files runnel's commands write, drawn with Matplotlib as PNG and PDF.

``python -m runnel plot OUT`` (or ``runnel-plot OUT``) looks at what the folder holds and draws it:

- ``runnel compare --out OUT``: ``hydrograph`` (the outflow over time of each model with a clock in seconds,
  from ``MODEL/outflow.csv``)
  and ``volumes`` (each model's eroded and deposited volume, from ``metrics.csv``);
- ``runnel validate overland --out OUT``: ``hydrograph``, each run's outflow over the rain on the plane
  (``RUN/outflow.csv``) beside the kinematic wave's, and ``profile``, the depths at the gauges beside the
  steady depth (``overland.json``);
- ``runnel validate hydrostatic --out OUT``: ``pressure``, each layer's pressure beside ρ0 g d
  (``pressure.csv``);
- ``runnel validate dambreak --out OUT``: ``front``, the surge front over time (``front.csv``) beside the
  experiment's points, a second reading of them and a peer code's (``front_reference.csv``);
- ``runnel validate mobile-bed --out OUT`` (``--models`` puts each model in ``OUT/MODEL``): ``gauges``, the
  water surface at the four gauges over time beside the measured one (``gauges.csv``), and ``profiles``, the
  final bed along the three profiles beside the repeats' band (``profiles.csv``);
- ``runnel sweep SWEEP.toml --out OUT``: ``METRIC_vs_PARAMETER``, each collected metric against each varied
  numeric parameter, one line per model, the mean over the other axes (``manifest.csv``, ``results.csv``);
- ``runnel run --out OUT`` with ``run.outflow_every``: ``hydrograph`` (``outflow.csv``).

The figures are written into ``OUT/figures/`` as ``NAME.png`` and ``NAME.pdf`` (beside the commands' own
map pictures); :func:`plot` returns the Matplotlib figures by name. A folder none of these wrote is refused with the files it would need.
"""
import csv
import pathlib

from . import InputError

FORMATS = ("png", "pdf")


def _read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise InputError(f"{path}: holds no rows")
    return {key: [float(r[key]) if _is_number(r[key]) else r[key] for r in rows] for key in rows[0]}


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def _figure(title, x_label, y_label):
    from matplotlib.figure import Figure

    figure = Figure(figsize=(6.4, 4.2), layout="constrained")
    axes = figure.add_subplot()
    axes.set_title(title)
    axes.set_xlabel(x_label)
    axes.set_ylabel(y_label)
    axes.grid(True, alpha=0.3)
    return figure, axes


def _hydrograph(runs, title, share_of_rain, colours=None):
    """Outflow against time for each (label, outflow.csv columns)."""
    figure, axes = _figure(title, "t (s)", "outflow / rain" if share_of_rain else "outflow (m³/s)")
    for label, table in runs:
        outflow = table["outflow"]
        if share_of_rain:
            rain = max(table["rain"])
            outflow = [q / rain for q in outflow] if rain > 0 else outflow
        axes.plot(table["t"], outflow, label=label, color=(colours or {}).get(label))
    axes.legend()
    return figure


def _compare(folder):
    metrics = _read_csv(folder / "metrics.csv")
    figures = {}
    # The models with a clock in seconds (an iteration is no time).
    runs = [(model, _read_csv(folder / model / "outflow.csv")) for model, clock in zip(metrics["model"], metrics["clock"])
            if clock == "s" and (folder / model / "outflow.csv").is_file()]
    if runs:
        figures["hydrograph"] = _hydrograph(runs, "the water leaving the terrain", share_of_rain=False)
    figure, axes = _figure("eroded and deposited volume", "model", "volume (m³)")
    models = metrics["model"]
    place = range(len(models))
    axes.bar([p - 0.2 for p in place], metrics["eroded_volume_m3"], width=0.4, label="eroded")
    axes.bar([p + 0.2 for p in place], metrics["deposited_volume_m3"], width=0.4, label="deposited")
    axes.set_xticks(list(place), models)
    axes.set_yscale("symlog", linthresh=1.0)
    axes.legend()
    figures["volumes"] = figure
    return figures


class KinematicPlane:
    """The kinematic wave for rain i on a plane of length L, slope S and Manning's n, raining for D
    (Woolhiser & Liggett 1967): q = (√S/n) h^(5/3), the analytic curves `runnel validate overland`
    scores against (docs/validation.md)."""

    def __init__(self, length, slope, manning_n, rain_mm_h, duration):
        self.length, self.duration = length, duration
        self.alpha = slope**0.5 / manning_n
        self.rain = rain_mm_h / 3.6e6

    def depth(self, x):
        """The steady depth at x, m."""
        return (self.rain * x / self.alpha) ** 0.6

    def equilibrium_time(self):
        return (self.length / (self.alpha * self.rain ** (2.0 / 3.0))) ** 0.6

    def outflow_share(self, t):
        """The outflow per unit width at the foot over i L, at time t."""
        i, a, length = self.rain, self.alpha, self.length
        if t <= 0:
            return 0.0
        if t <= self.duration:
            return min(1.0, a * (i * t) ** (5.0 / 3.0) / (i * length))
        # After the rain: the characteristic that reaches the foot at t started at x0 with depth h,
        # x0 = a h^(5/3) / i, and moved at (5/3) a h^(2/3) since the rain stopped.
        low, high = 0.0, self.depth(length)
        for _ in range(60):
            h = 0.5 * (low + high)
            if a * h ** (5.0 / 3.0) / i + (5.0 / 3.0) * a * h ** (2.0 / 3.0) * (t - self.duration) > length:
                high = h
            else:
                low = h
        return a * low ** (5.0 / 3.0) / (i * length)


def _overland(folder):
    runs = [(path.parent.name, _read_csv(path)) for path in sorted(folder.glob("*/outflow.csv"))]
    colours = {label: f"C{k}" for k, (label, _) in enumerate(runs)}  # one colour a run in both figures
    figure = _hydrograph(runs, "rain off the plane: the outflow hydrograph", share_of_rain=True, colours=colours)
    figures = {"hydrograph": figure}
    case_file = folder / "overland.json"
    if not case_file.is_file():
        return figures
    import json

    case = json.loads(case_file.read_text())
    plane = KinematicPlane(case["length_m"], case["slope"], case["manning_n"], case["rain_mm_h"],
                           case["rain_duration_s"])
    end = max(max(table["t"]) for _, table in runs) if runs else 2 * plane.duration
    times = [end * k / 400 for k in range(401)]
    figure.axes[0].plot(times, [plane.outflow_share(t) for t in times], color="black", label="kinematic wave")
    figure.axes[0].legend()
    profile, axes = _figure("the depth at equilibrium", "x (m)", "depth (m)")
    xs = [plane.length * k / 200 for k in range(201)]
    axes.plot(xs, [plane.depth(x) for x in xs], color="black", label="kinematic wave")
    for run in case["runs"]:
        gauges = run.get("gauges", [])
        label = run["run"] + (f"-{run['spacing_m']:g}" if "spacing_m" in run else "")  # its folder's name
        if gauges:
            axes.plot([g["x_m"] for g in gauges], [g["depth_m"] for g in gauges], "o", label=label,
                      color=colours.get(label))
    axes.legend()
    figures["profile"] = profile
    return figures


def _hydrostatic(folder):
    table = _read_csv(folder / "pressure.csv")
    figure, axes = _figure("hydrostatic tank: pressure against depth", "depth (m)", "pressure (Pa)")
    axes.plot(table["depth"], table["expected"], color="black", label="ρ0 g d")
    axes.plot(table["depth"], table["pressure"], "o", label="runnel, per layer")
    axes.legend()
    return {"pressure": figure}


def _dambreak(folder):
    table = _read_csv(folder / "front.csv")
    figure, axes = _figure("dam break: the surge front", "t* = t √(g/L)", "x / L")
    reference = folder / "front_reference.csv"
    if reference.is_file():
        points = _read_csv(reference)
        for source, marker in zip(dict.fromkeys(points["source"]), ("s", "^", "o")):
            rows = [k for k, s in enumerate(points["source"]) if s == source]
            axes.plot([points["t_star"][k] for k in rows], [points["x_over_L"][k] for k in rows], marker,
                      fillstyle="none", label=source)
    axes.plot(table["t_star"], table["x_over_L"], color="C3", label="runnel")
    axes.legend()
    return {"front": figure}


def _mobile_bed(folder):
    """The Soares-Frazão et al. (2012) flume: one folder's model, or each model's ``MODEL/`` folder."""
    folders = [folder] if (folder / "gauges.csv").is_file() else sorted(p.parent for p in folder.glob("*/gauges.csv"))
    for f in folders:
        if not (f / "profiles.csv").is_file():
            raise InputError(f"{f / 'profiles.csv'}: missing (runnel validate mobile-bed writes it beside gauges.csv)")
    gauges = [_read_csv(f / "gauges.csv") for f in folders]
    profiles = [_read_csv(f / "profiles.csv") for f in folders]
    from matplotlib.figure import Figure

    figures = {}
    names = list(dict.fromkeys(gauges[0]["gauge"]))
    figure = Figure(figsize=(3.2 * len(names), 3.4), layout="constrained")
    figure.suptitle("Soares-Frazão et al. 2012: the water surface at the gauges")
    for g, name in enumerate(names):
        axes = figure.add_subplot(1, len(names), g + 1)
        axes.set_title(name)
        axes.set_xlabel("t (s)")
        if g == 0:
            axes.set_ylabel("water surface (m)")
        axes.grid(True, alpha=0.3)
        for m, table in enumerate(gauges):
            for source in dict.fromkeys(table["source"]):
                if source == "measured" and m > 0:
                    continue  # the experiment once
                rows = [k for k in range(len(table["t"])) if table["gauge"][k] == name and table["source"][k] == source]
                style = {"color": "black", "marker": "o", "markersize": 2, "linestyle": "none"} if source == "measured" else {}
                axes.plot([table["t"][k] for k in rows], [table["surface"][k] for k in rows], label=source, **style)
        if g == 0:
            axes.legend(fontsize="small")
    figures["gauges"] = figure
    names = list(dict.fromkeys(profiles[0]["profile"]))
    figure = Figure(figsize=(4.2 * len(names), 3.4), layout="constrained")
    figure.suptitle("Soares-Frazão et al. 2012: the final bed")
    for p, name in enumerate(names):
        axes = figure.add_subplot(1, len(names), p + 1)
        first = profiles[0]
        rows = [k for k in range(len(first["x"])) if first["profile"][k] == name]
        axes.set_title(f"{name} (y = {first['y'][rows[0]]:g} m)")
        axes.set_xlabel("x (m)")
        if p == 0:
            axes.set_ylabel("bed (m)")
        axes.grid(True, alpha=0.3)
        x = [first["x"][k] for k in rows]
        axes.fill_between(x, [first["low"][k] for k in rows], [first["high"][k] for k in rows], color="0.8",
                          label="the repeats' band")
        axes.plot(x, [first["mean"][k] for k in rows], color="black", linewidth=0.8, label="the repeats' mean")
        for table in profiles:
            rows = [k for k in range(len(table["x"])) if table["profile"][k] == name]
            axes.plot([table["x"][k] for k in rows], [table["simulated"][k] for k in rows], label=table["model"][rows[0]])
        if p == 0:
            axes.legend(fontsize="small")
    figures["profiles"] = figure
    return figures


def _sweep(folder):
    """Each metric against each varied numeric parameter, a line per model (the mean over the other axes)."""
    with open(folder / "manifest.csv", newline="") as f:
        header = next(csv.reader(f))
    axes_names = header[1:header.index("state")]
    with open(folder / "results.csv", newline="") as f:
        members = list(csv.DictReader(f))
    if not members:
        raise InputError(f"{folder / 'results.csv'}: no member is done yet; nothing to draw")
    metrics = [name for name in members[0] if name != "member" and name not in axes_names]
    models = dict.fromkeys(m.get("run.model", "") for m in members)
    figures = {}
    for axis in axes_names:
        if axis == "run.model" or not all(_is_number(m[axis]) for m in members):
            continue  # only numeric parameters have an x axis
        for metric in metrics:
            figure, plot_axes = _figure(f"{metric} against {axis}", axis, metric)
            for model in models:
                sums = {}
                for m in members:
                    if m.get("run.model", "") != model or not _is_number(m[metric]):
                        continue
                    total, count = sums.get(float(m[axis]), (0.0, 0))
                    sums[float(m[axis])] = (total + float(m[metric]), count + 1)
                x = sorted(sums)
                if x:
                    plot_axes.plot(x, [sums[v][0] / sums[v][1] for v in x], "o-", label=model or "members")
            plot_axes.legend()
            figures[f"{metric}_vs_{axis}"] = figure
    if not figures:
        raise InputError(f"{folder}: the sweep varies no numeric parameter to draw its metrics against")
    return figures


def _run(folder):
    return {"hydrograph": _hydrograph([("runnel", _read_csv(folder / "outflow.csv"))], "the water leaving the terrain",
                                      share_of_rain=False)}


# What each command leaves in its folder, in the order they are recognised.
_KINDS = (
    ("runnel compare", lambda f: (f / "metrics.csv").is_file() and (f / "report.md").is_file(), _compare),
    ("runnel validate hydrostatic", lambda f: (f / "pressure.csv").is_file(), _hydrostatic),
    ("runnel validate dambreak", lambda f: (f / "front.csv").is_file(), _dambreak),
    ("runnel validate mobile-bed", lambda f: (f / "gauges.csv").is_file() or any(f.glob("*/gauges.csv")), _mobile_bed),
    ("runnel sweep", lambda f: (f / "manifest.csv").is_file() and (f / "results.csv").is_file(), _sweep),
    ("runnel run", lambda f: (f / "outflow.csv").is_file(), _run),
    ("runnel validate overland", lambda f: any(f.glob("*/outflow.csv")), _overland),
)


def plot(folder, formats=FORMATS):
    """Draws the figures of a folder a runnel command wrote, into its ``figures/`` folder.

    Parameters
    ----------
    folder : str or path-like
        The command's ``--out`` folder.
    formats : tuple of str, optional
        The files written for each figure (default PNG and PDF).

    Returns
    -------
    dict
        The Matplotlib figures by name (``hydrograph``, ``volumes``, ``profile``, ``pressure``, ``front``,
        ``gauges``, ``profiles``, ``METRIC_vs_PARAMETER``).
    """
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        raise InputError(f"{folder}: not a folder")
    for _, recognise, draw in _KINDS:
        if recognise(folder):
            figures = draw(folder)
            (folder / "figures").mkdir(exist_ok=True)
            for name, figure in figures.items():
                for extension in formats:
                    figure.savefig(folder / "figures" / f"{name}.{extension}", dpi=200)
            return figures
    raise InputError(
        f"{folder}: holds none of the files runnel-plot draws: metrics.csv and report.md (runnel compare), "
        "pressure.csv (validate hydrostatic), front.csv (validate dambreak), gauges.csv and profiles.csv "
        "(validate mobile-bed), manifest.csv and results.csv (runnel sweep), outflow.csv (runnel run with "
        "run.outflow_every) or RUN/outflow.csv (validate overland)"
    )


def main(argv=None):
    """``runnel-plot OUT``: draws a folder's figures; exit 2 with one line on stderr for a bad folder."""
    import sys

    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1 or args[0] in ("-h", "--help"):
        sys.stderr.write("usage: runnel-plot OUT   (the --out folder of runnel compare, run, sweep or validate)\n")
        return 0 if args and args[0] in ("-h", "--help") else 2
    try:
        figures = plot(args[0])
    except InputError as error:
        sys.stderr.write(f"runnel-plot: {error}\n")
        return 2
    names = ", ".join(f"{name}.{extension}" for name in figures for extension in FORMATS)
    sys.stdout.write(f"runnel-plot: wrote {names} in {pathlib.Path(args[0]) / 'figures'}\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
