#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Python package: a virtual environment in .venv (seeing Debian's NumPy, Matplotlib, h5py and
# pytest), the real clients the suite tests against from PyPI (bmipy, bmi-tester with gimli.units
# for its units check, Landlab, xarray and netCDF4, the CF checker, nbclient for the notebooks, MkDocs for the
# docs site), and `pip install .` of
# runnel itself (scikit-build-core builds the C++ core, the pybind11 module and the CLI with
# CMake). The build folder is the environment's own (.venv/runnel-build), so a reinstall compiles
# only what changed. Idempotent. Afterwards: .venv/bin/python -c "import runnel"
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ ! -x .venv/bin/python ]; then
  /usr/bin/python3 -m venv --system-site-packages .venv
fi
pip=(.venv/bin/python -m pip install --quiet --disable-pip-version-check -c python/constraints.txt)
# gimli.units 0.3: bmi-tester 0.5 imports gimli.units, which 0.4 no longer provides (its units
# check would be skipped).
"${pip[@]}" "bmipy>=2,<3" "bmi-tester>=0.5,<0.6" "gimli.units>=0.3.4,<0.4" "scikit-build-core>=0.8,<2" \
  "landlab>=2.7" "xarray>=2023" "netCDF4>=1.6" "cfchecker>=4.1,<4.2" nbclient nbformat ipykernel \
  matplotlib-inline "mkdocs>=1.6,<2" "mkdocs-material>=9,<10" "mkdocstrings[python]>=1,<2" \
  "mkdocs-jupyter>=0.25,<1"
# --no-build-isolation: build with the environment's scikit-build-core and Debian's pybind11.
CMAKE_BUILD_PARALLEL_LEVEL="$(nproc)" "${pip[@]}" --no-build-isolation \
  --config-settings=build-dir="$PWD/.venv/runnel-build/{wheel_tag}" .
.venv/bin/python -c "import runnel; print('setup-python: runnel', runnel.__version__, 'in .venv')"
