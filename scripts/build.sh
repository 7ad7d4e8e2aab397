#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configures and builds runnel into build/, or $RUNNEL_BUILD_DIR (Release, -Wall -Wextra);
# $RUNNEL_CMAKE_ARGS adds configure options.
set -euo pipefail
cd "$(dirname "$0")/.."
# The Python module is built for Debian's python3 (its headers come with python3-dev); its tests
# run in the package's virtual environment when scripts/setup-python.sh made one.
python_args=()
if [ -x /usr/bin/python3 ]; then python_args+=(-DPython3_EXECUTABLE=/usr/bin/python3); fi
if [ -x .venv/bin/python ]; then python_args+=(-DRUNNEL_TEST_PYTHON="$PWD/.venv/bin/python"); fi
build_dir="${RUNNEL_BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${python_args[@]}" ${RUNNEL_CMAKE_ARGS:-} >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
