#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The README's main job: installs what is missing, builds, and runs the built-in default scenario.
# Outputs go to out/default/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out/default
./build/runnel generate --scenario data/scenarios/default.toml -o out/default/terrain.asc
./build/runnel convert out/default/terrain.asc out/default/terrain.png
./build/runnel convert out/default/terrain.asc out/default/terrain.npy
./build/runnel info out/default/terrain.asc
