#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Python package: a virtual environment in .venv (seeing Debian's NumPy, Matplotlib, h5py and
# pytest), bmipy and bmi-tester from PyPI, and `pip install .` of runnel itself (scikit-build-core
# builds the C++ core and the pybind11 module with CMake; build-python/ keeps the build, so a
# reinstall compiles only what changed). Idempotent. Afterwards: .venv/bin/python -c "import runnel"
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ ! -x .venv/bin/python ]; then
  /usr/bin/python3 -m venv --system-site-packages .venv
fi
pip=(.venv/bin/python -m pip install --quiet --disable-pip-version-check)
"${pip[@]}" "bmipy>=2,<3" "bmi-tester>=0.5,<0.6" "scikit-build-core>=0.8,<2"
# --no-build-isolation: build with the environment's scikit-build-core and Debian's pybind11.
CMAKE_BUILD_PARALLEL_LEVEL="$(nproc)" "${pip[@]}" --no-build-isolation .
.venv/bin/python -c "import runnel; print('setup-python: runnel', runnel.__version__, 'in .venv')"
