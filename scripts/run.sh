#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The README's main job: installs what is missing, builds, and runs rain erosion on the built-in
# default scenario. Outputs go to out/default/ (pictures, final terrain, metrics.json).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/runnel run data/scenarios/default.toml --out out/default
