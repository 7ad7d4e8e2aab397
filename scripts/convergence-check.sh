#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Does SPH erosion converge on terrains it was not tuned for? Runs `runnel validate
# erosion-convergence` (the eroded volume against half the time step, half the particle size, spawn
# heights of 0.5 and 2 spacings and twice the speed of sound) on the default's fBm hills and on
# four 65 x 65 terrains with the same 2 m cells: ridged hills, and the middle of three crops of the
# Jacksboro DEM, with each run's peak Mach number and density compression. Not part of the test
# suite: 3-10 minutes a terrain on 2 cores (11 minutes for the first three at a quiet hour).
# Usage: scripts/convergence-check.sh [OUT]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/convergence}"
runnel=./build/runnel
mkdir -p "$out"
"$runnel" generate ridged --size 65 --cell 2 --seed 7 --set relief=0.08 --set hurst=1.0 --set octaves=5 \
  -o "$out/ridged65.asc" >/dev/null
# The central 65 x 65 vertices of each 129 x 129 crop of the DEM (its rows and columns 32..96).
middle() {
  awk 'NR <= 6 { if ($1 == "ncols" || $1 == "nrows") $2 = 65; print; next }
       NR - 7 >= 32 && NR - 7 <= 96 { line = $33; for (k = 34; k <= 97; ++k) line = line " " $k; print line }' "$1"
}
middle data/terrains/jacksboro_crop_scaled.asc >"$out/jacksboro65.asc"
middle data/terrains/jacksboro_nw_scaled.asc >"$out/jacksboro_nw65.asc"
middle data/terrains/jacksboro_se_scaled.asc >"$out/jacksboro_se65.asc"
names=(fbm ridged65 jacksboro65 jacksboro_nw65 jacksboro_se65)
declare -A terrain=([fbm]="" [ridged65]="--terrain $out/ridged65.asc" [jacksboro65]="--terrain $out/jacksboro65.asc"
  [jacksboro_nw65]="--terrain $out/jacksboro_nw65.asc" [jacksboro_se65]="--terrain $out/jacksboro_se65.asc")
for name in "${names[@]}"; do
  # shellcheck disable=SC2086  # the options are words on purpose
  "$runnel" validate erosion-convergence ${terrain[$name]} >"$out/$name.json"
done
printf '%-12s %-13s %10s %8s %8s %9s %9s\n' terrain variant eroded_m3 change dh_corr peak_Ma peak_Δρ/ρ0
for name in "${names[@]}"; do
  /usr/bin/python3 - "$out/$name.json" "$name" <<'PY'
import json, sys
for r in json.load(open(sys.argv[1]))["details"]["runs"]:
    print(f"{sys.argv[2]:12s} {r['variant']:13s} {r['eroded_m3']:10.1f} {100 * r['relative_change']:7.2f}%"
          f" {r['dh_correlation_with_base']:8.3f} {r['peak_mach']:9.3f} {100 * r['peak_compression']:8.1f}%")
PY
done
