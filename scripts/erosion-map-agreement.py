#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""How alike two runs' erosion is, terrain by terrain: the eroded volumes and the correlation of the
two Δh maps smoothed over 4 × 4 cells (what the solvers are compared on in docs/validation.md).

Usage: python3 scripts/erosion-map-agreement.py A B [MODEL] [--by-area]
A and B are two output folders of scripts/drainage-check.sh (say one per solver, or one per seed); MODEL is
the model folder compared in each (default sph). Reads each terrain's MODEL/erosion.tif (Δh, m) with GDAL and
MODEL/metrics.json. With --by-area, also where the maps differ: the cells grouped by their drainage area (A's
MODEL/drainage_area.npy, split at its 50th, 80th, 95th and 99th percentiles, hillslopes to main channels), and
in each class the sum of Δh over the cells lowered and over the cells raised (m), for A and for B."""
import json
import pathlib
import sys

import numpy as np
from osgeo import gdal


def smoothed(dh, cells=4):
    """The mean of every cells × cells window (a box filter, valid part only)."""
    c = np.cumsum(np.cumsum(np.pad(dh, ((1, 0), (1, 0))), axis=0), axis=1)
    return (c[cells:, cells:] - c[:-cells, cells:] - c[cells:, :-cells] + c[:-cells, :-cells]) / cells**2


AREA_PERCENTILES = (50, 80, 95, 99)


def by_area(a, terrain, model, maps):
    """Per drainage-area class (A's drainage areas), the lowered and the raised cells' Δh summed, A's map
    then B's (`maps`, unsmoothed)."""
    area = np.load(a / terrain / model / "drainage_area.npy").astype(float)
    edges = [area.min()] + list(np.percentile(area, AREA_PERCENTILES)) + [area.max() + 1]
    print(f"  {'class (percentile of area)':27s} {'lowered A':>9s} {'lowered B':>9s} {'raised A':>9s} {'raised B':>9s}")
    bounds = (0,) + AREA_PERCENTILES + (100,)
    for k in range(len(edges) - 1):
        cls = (area >= edges[k]) & (area < edges[k + 1])
        sums = [(-dh[cls & (dh < 0)].sum(), dh[cls & (dh > 0)].sum()) for dh in maps]
        label = f"{bounds[k]}-{bounds[k + 1]}"
        print(f"  {label:27s} {sums[0][0]:9.0f} {sums[1][0]:9.0f} {sums[0][1]:9.0f} {sums[1][1]:9.0f}")


def main():
    args = [x for x in sys.argv[1:] if x != "--by-area"]
    areas = len(args) < len(sys.argv) - 1
    a, b = pathlib.Path(args[0]), pathlib.Path(args[1])
    model = args[2] if len(args) > 2 else "sph"
    print(f"{'terrain':13s} {'eroded A':>9s} {'eroded B':>9s} {'B/A-1':>7s} {'Δh corr':>8s}")
    for terrain in sorted(p.name for p in a.iterdir() if (p / model / "erosion.tif").exists()):
        maps, eroded = [], []
        for run in (a, b):
            maps.append(gdal.Open(str(run / terrain / model / "erosion.tif")).ReadAsArray().astype(float))
            eroded.append(json.loads((run / terrain / model / "metrics.json").read_text())["eroded_volume"])
        corr = np.corrcoef(smoothed(maps[0]).ravel(), smoothed(maps[1]).ravel())[0, 1]
        print(f"{terrain:13s} {eroded[0]:9.0f} {eroded[1]:9.0f} {eroded[1] / eroded[0] - 1:+7.1%} {corr:8.3f}")
        if areas:
            by_area(a, terrain, model, maps)


if __name__ == "__main__":
    main()
