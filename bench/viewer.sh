#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The painting loop's speed (docs/performance.md, "The viewer"): for each solver and particle count,
# a checkpoint of the default storm holding that many particles (runnel run), then runnel-viewer
# --bench on it at 1280 x 800, drawn off-screen through EGL (--headless: no display needed): one
# JSON line each, frames per second, simulated seconds per wall second, the share of the frame spent
# drawing and on the water, and each phase's milliseconds.
# Usage: bench/viewer.sh [OUT [COUNTS [SOLVERS]]], e.g. bench/viewer.sh out/viewer-bench 20000,200000 wcsph,dfsph
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/viewer-bench}"
IFS=, read -r -a counts <<<"${2:-20000,200000}"
IFS=, read -r -a solvers <<<"${3:-wcsph,dfsph}"
mkdir -p "$out"
for solver in "${solvers[@]}"; do
  for n in "${counts[@]}"; do
    # Rain that keeps about n particles alive (rate × lifespan), run until the budget has filled.
    ./build/runnel run data/scenarios/default.toml --set sph.solver="$solver" \
      --set rain.max_particles="$n" --set rain.rate="$((n / 4))" --set run.sim_time=5 \
      --quiet --overwrite --out "$out/$solver-$n" >/dev/null
    ./build/runnel-viewer "$out/$solver-$n/final.h5" --headless --bench --frames 60 --size 1280x800
  done
done
