# SPDX-License-Identifier: MIT
# runnel from Python, notebook style: a real DEM, two erosion models, their metrics, one figure.
# Run it from the repository root: python docs/python/example.py [OUTPUT.png]; it needs Matplotlib
# (pip install "runnel-erosion[plot]").
# (The suite runs it: docs/python/test_example.py.)
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import runnel  # noqa: E402

# %% A real DEM: the Jacksboro fault, Tennessee (USGS, 83 m cells); GeoTIFF works the same way.
dem = runnel.read_terrain("data/terrains/jacksboro_fault_dem.asc")
print(dem, f"heights {dem.heights.min():.0f}..{dem.heights.max():.0f} m")

# %% Two models on the same terrain: virtual-pipe shallow water (60 s of a heavy storm) and the
# cellular-automaton hydraulic model (200 iterations).
pipe = runnel.Model("pipe", dem, {"pipe.rain": 0.005, "run.seed": 1})
pipe.advance(60.0)
olsen = runnel.Model("olsen", dem, {"run.seed": 1})
olsen.advance(200)

# %% Exact mass balance and the shared metrics (docs/metrics.md).
for model in (pipe, olsen):
    balance = model.mass_balance()
    metrics = runnel.terrain_metrics(model.initial_terrain(), model.terrain())
    print(f"{model.name:6s} eroded {balance['eroded']:10.1f} m3, residual {balance['residual']} m3, "
          f"erosion-flow correlation {metrics['erosion_flow_correlation']:+.2f}")

# %% Where each model took material away (red) and put it down (blue).
fig, axes = plt.subplots(1, 3, figsize=(13, 4), constrained_layout=True)
axes[0].imshow(dem.heights, cmap="terrain")
axes[0].set_title("Jacksboro DEM (m)")
for ax, model in zip(axes[1:], (pipe, olsen)):
    change = model.terrain().heights - model.initial_terrain().heights
    limit = float(np.percentile(np.abs(change), 99)) or 1e-6
    image = ax.imshow(change, cmap="RdBu", vmin=-limit, vmax=limit)
    ax.set_title(f"{model.name}: height change (m)")
    fig.colorbar(image, ax=ax, shrink=0.8)
for ax in axes:
    ax.set_xticks([])
    ax.set_yticks([])
output = sys.argv[1] if len(sys.argv) > 1 else "runnel_example.png"
fig.savefig(output, dpi=80)
print("figure:", output)
