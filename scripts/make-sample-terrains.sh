#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Regenerates the generated sample terrains in data/terrains/ (bit for bit: the generators are deterministic).
set -euo pipefail
cd "$(dirname "$0")/.."
r=./build/runnel
$r generate fbm --size 257 --cell 2 --seed 7 -o data/terrains/fbm_257.png
$r generate v-valley --size 129 --cell 1 -o data/terrains/v_valley_129.asc
$r generate ridged --size 257 --cell 4 --seed 3 --set relief=0.15 -o data/terrains/ridged_257.npy
