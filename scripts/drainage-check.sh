#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Does SPH erosion follow the water on terrains it was not tuned for? Runs `runnel compare` (SPH and
# the pipe model, the same rain budget) with the default scenario's physics on seven terrains, only
# the terrain changing, and prints the drainage metrics of docs/metrics.md for each. Not part of
# the test suite: about 3 minutes a terrain on 2 cores. Usage: scripts/drainage-check.sh [OUT [--set
# KEY=VALUE ...]]: the options after OUT go to every `runnel compare` (one physics setting changed on
# every terrain, e.g. --set erosion.exchange_interval=0.01).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/drainage}"
shift $(($# > 0 ? 1 : 0))
runnel=./build/runnel
scenario=data/scenarios/default.toml
mkdir -p "$out"
# The ridged terrains: one within the talus angle (relief 8 %, five octaves), one far rougher than a
# 2 m grid holds (the generator's 8 octaves at the default's 12 % relief: 16 % of its edges steeper
# than the 40° talus angle).
"$runnel" generate ridged --size 129 --cell 2 --seed 7 --set relief=0.08 --set hurst=1.0 --set octaves=5 \
  -o "$out/ridged.npy" >/dev/null
"$runnel" generate ridged --size 129 --cell 2 --seed 7 --set relief=0.12 -o "$out/ridged_rough.npy" >/dev/null
names=(fbm_seed7 fbm_seed11 ridged ridged_rough jacksboro jacksboro_nw jacksboro_se)  # the table's order
declare -A terrain=(
  [fbm_seed7]=""                       # the default scenario itself
  [fbm_seed11]="--set terrain.seed=11" # other hills from the same generator
  [ridged]="--terrain $out/ridged.npy"
  [ridged_rough]="--terrain $out/ridged_rough.npy"
  [jacksboro]="--terrain data/terrains/jacksboro_crop_scaled.asc" # a real DEM's valleys, scaled 1:41.5
  # Two more crops of the same DEM, never tuned on (data/README.md).
  [jacksboro_nw]="--terrain data/terrains/jacksboro_nw_scaled.asc"
  [jacksboro_se]="--terrain data/terrains/jacksboro_se_scaled.asc"
)
for name in "${names[@]}"; do
  # shellcheck disable=SC2086  # the options are words on purpose
  "$runnel" compare "$scenario" --models sph,pipe ${terrain[$name]} "$@" --out "$out/$name" --quiet
done
printf '%-13s %-5s %9s %9s %8s %7s %12s %7s %7s\n' terrain model eroded deposited ρ_sp ρ_flow depressions shortλ roughen
for name in "${names[@]}"; do
  /usr/bin/python3 - "$out/$name/metrics.csv" "$name" <<'PY'
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    print(f"{sys.argv[2]:13s} {r['model']:5s} {float(r['eroded_volume_m3']):9.0f} {float(r['deposited_volume_m3']):9.0f}"
          f" {float(r['stream_power_correlation']):+8.3f} {float(r['erosion_flow_correlation']):+7.3f}"
          f" {r['closed_depressions']:>5s}/{r['closed_depressions_initial']:<6s} {float(r['short_wavelength_dh_share']):7.3f}"
          f" {float(r['short_wavelength_power_ratio']):7.3f}")
PY
done
