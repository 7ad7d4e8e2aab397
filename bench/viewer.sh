#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The painting loop's speed (docs/performance.md, "The viewer"): for each solver and particle count,
# a checkpoint of the default storm holding that many particles (runnel run), then runnel-viewer
# --bench on it at 1280 x 800: one JSON line each, frames per second and simulated seconds per
# wall second while simulating and drawing. Under Xvfb when there is no display.
# Usage: bench/viewer.sh [OUT [COUNTS [SOLVERS]]], e.g. bench/viewer.sh out/viewer-bench 20000,200000 wcsph,dfsph
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/viewer-bench}"
IFS=, read -r -a counts <<<"${2:-20000,200000}"
IFS=, read -r -a solvers <<<"${3:-wcsph,dfsph}"
mkdir -p "$out"
if [ -z "${DISPLAY:-}" ]; then
  display=":$((90 + RANDOM % 100))"
  Xvfb "$display" -screen 0 1400x900x24 -nolisten tcp >/dev/null 2>&1 &
  xvfb=$!
  trap 'kill $xvfb 2>/dev/null || true' EXIT
  for _ in $(seq 50); do DISPLAY=$display xdpyinfo >/dev/null 2>&1 && break; sleep 0.1; done
  export DISPLAY=$display
fi
for solver in "${solvers[@]}"; do
  for n in "${counts[@]}"; do
    # Rain that keeps about n particles alive (rate × lifespan), run until the budget has filled.
    ./build/runnel run data/scenarios/default.toml --set sph.solver="$solver" \
      --set rain.max_particles="$n" --set rain.rate="$((n / 4))" --set run.sim_time=5 \
      --quiet --overwrite --out "$out/$solver-$n" >/dev/null
    ./build/runnel-viewer "$out/$solver-$n/final.h5" --bench --frames 60 --size 1280x800
  done
done
