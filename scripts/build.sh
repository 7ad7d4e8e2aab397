#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configures and builds runnel into build/ (Release, -Wall -Wextra).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${RUNNEL_CMAKE_ARGS:-} >/dev/null
cmake --build build -j "$(nproc)"
