#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""How alike two runs' erosion is, terrain by terrain: the eroded volumes and the correlation of the
two Δh maps smoothed over 4 × 4 cells (what the solvers are compared on in docs/validation.md).

Usage: python3 scripts/erosion-map-agreement.py A B [MODEL]
A and B are two output folders of scripts/drainage-check.sh (say one per solver, or one per seed); MODEL is
the model folder compared in each (default sph). Reads each terrain's MODEL/erosion.tif (Δh, m) with GDAL and
MODEL/metrics.json."""
import json
import pathlib
import sys

import numpy as np
from osgeo import gdal


def smoothed(dh, cells=4):
    """The mean of every cells × cells window (a box filter, valid part only)."""
    c = np.cumsum(np.cumsum(np.pad(dh, ((1, 0), (1, 0))), axis=0), axis=1)
    return (c[cells:, cells:] - c[:-cells, cells:] - c[cells:, :-cells] + c[:-cells, :-cells]) / cells**2


def main():
    a, b = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    model = sys.argv[3] if len(sys.argv) > 3 else "sph"
    print(f"{'terrain':13s} {'eroded A':>9s} {'eroded B':>9s} {'B/A-1':>7s} {'Δh corr':>8s}")
    for terrain in sorted(p.name for p in a.iterdir() if (p / model / "erosion.tif").exists()):
        maps, eroded = [], []
        for run in (a, b):
            maps.append(smoothed(gdal.Open(str(run / terrain / model / "erosion.tif")).ReadAsArray().astype(float)))
            eroded.append(json.loads((run / terrain / model / "metrics.json").read_text())["eroded_volume"])
        corr = np.corrcoef(maps[0].ravel(), maps[1].ravel())[0, 1]
        print(f"{terrain:13s} {eroded[0]:9.0f} {eroded[1]:9.0f} {eroded[1] / eroded[0] - 1:+7.1%} {corr:8.3f}")


if __name__ == "__main__":
    main()
