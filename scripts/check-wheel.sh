#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The install a researcher does, in one try: a fresh virtual environment (nothing from Debian's Python
# packages), `pip install ".[all]"` from this checkout (the wheel built in pip's own isolated build
# environment, PyPI's numpy and all), then `import runnel` and every extra's own import, a run through
# the package, and `python -m runnel --version`. Needs the network (PyPI) and the build tools
# scripts/setup.sh installs; takes minutes, so it is a script, not a test of the suite.
# Usage: bash scripts/check-wheel.sh [WORK_DIR]   (default: a temporary folder, removed afterwards)
set -euo pipefail
cd "$(dirname "$0")/.."
work="${1:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
if ! /usr/bin/python3 -c "import urllib.request; urllib.request.urlopen('https://pypi.org/simple/pip/', timeout=20)" \
  2>/dev/null; then
  echo "check-wheel: skipped: PyPI is not reachable, and a fresh environment installs from it"
  exit 77
fi
start=$(date +%s)
/usr/bin/python3 -m venv "$work/venv"
py="$work/venv/bin/python"
"$py" -m pip install --quiet --disable-pip-version-check --upgrade pip
CMAKE_BUILD_PARALLEL_LEVEL="$(nproc)" "$py" -m pip install --quiet --disable-pip-version-check \
  -c python/constraints.txt ".[all]"
"$py" - <<'PY'
import importlib
import runnel
for extra in ("matplotlib", "bmipy", "landlab", "xarray", "netCDF4"):
    importlib.import_module(extra)
from runnel.bmi import RunnelBmi  # noqa: F401  (the bmi extra's component)
import numpy as np
model = runnel.Model("pipe", runnel.Terrain(np.add.outer(np.arange(9.0), np.arange(9.0)), 1.0))
model.advance(1.0)
ds = model.to_xarray()
assert ds.height.shape == (1, 9, 9)
print("check-wheel: runnel", runnel.__version__, "and every extra import; a pipe model ran 1 s")
PY
"$py" -m runnel --version
echo "check-wheel: $(( $(date +%s) - start )) s"
